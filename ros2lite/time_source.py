"""The time source of a node (rclpy.time_source's shape): it follows the node's
``use_sim_time`` parameter and, while that is true, drives the ROS clocks attached to it from
the ``/clock`` topic.

Every node has one for its own clock (``node.get_clock()``); more can be made, for clocks of
one's own, with ``TimeSource(node=node).attach_clock(ROSClock())``.
"""

from __future__ import annotations

import contextlib
import threading
import weakref
from typing import TYPE_CHECKING

from ros2lite.clock import ROSClock
from ros2lite.parameter import Parameter
from ros2lite.parameters.store import result
from ros2lite.qos import QoSProfile, ReliabilityPolicy
from ros2lite.time import ClockType, Time

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces.msg import SetParametersResult
    from ros2lite.msgs.rosgraph_msgs.msg import Clock as ClockMsg
    from ros2lite.node_interface import NodeInterface
    from ros2lite.subscription import Subscription

__all__ = ['CLOCK_TOPIC', 'USE_SIM_TIME_NAME', 'TimeSource']

CLOCK_TOPIC = '/clock'
USE_SIM_TIME_NAME = 'use_sim_time'
# rclpy's: only the newest time matters, and a lost one is replaced by the next
CLOCK_QOS = QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)


class TimeSource:
    """Keeps its attached ROS clocks on system time, or on `/clock` under sim time."""

    def __init__(self, *, node: NodeInterface | None = None) -> None:
        self._lock = threading.RLock()
        self._clock_sub: Subscription[ClockMsg] | None = None
        self._node_weak_ref: weakref.ref[NodeInterface] | None = None
        self._associated_clocks: list[ROSClock] = []
        self._last_time_set: Time | None = None
        self._ros_time_is_active = False
        if node is not None:
            self.attach_node(node)

    # -- ROS time on/off ----------------------------------------------------------------------
    @property
    def ros_time_is_active(self) -> bool:
        """Whether the attached clocks follow /clock (use_sim_time)."""
        return self._ros_time_is_active

    @ros_time_is_active.setter
    def ros_time_is_active(self, enabled: bool) -> None:
        """Switch every attached clock to /clock time (subscribing to it) or back."""
        with self._lock:
            if bool(enabled) == self._ros_time_is_active:
                return
            self._ros_time_is_active = bool(enabled)
            for clock in self._associated_clocks:
                clock.set_ros_time_is_active(enabled)
            if enabled:
                self._subscribe_to_clock_topic()
            else:
                self._unsubscribe()

    def _subscribe_to_clock_topic(self) -> None:
        node = self._get_node()
        if self._clock_sub is None and node is not None:
            self._clock_sub = node.create_subscription(
                'rosgraph_msgs/msg/Clock', CLOCK_TOPIC, self.clock_callback, CLOCK_QOS
            )

    def _unsubscribe(self) -> None:
        sub, self._clock_sub = self._clock_sub, None
        node = self._get_node()
        if sub is not None and node is not None:
            node.destroy_subscription(sub)

    def clock_callback(self, msg: ClockMsg) -> None:
        """A `/clock` message: the new time of every attached clock."""
        time_point = Time.from_msg(msg.clock)
        with self._lock:
            self._last_time_set = time_point
            clocks = list(self._associated_clocks)
        for clock in clocks:
            clock.set_ros_time_override(time_point)

    # -- node ---------------------------------------------------------------------------------
    def _get_node(self) -> NodeInterface | None:
        return self._node_weak_ref() if self._node_weak_ref is not None else None

    def attach_node(self, node: NodeInterface) -> None:
        """Follow `node`'s `use_sim_time` (declared here if the node has none yet)."""
        with self._lock:
            if self._node_weak_ref is not None:
                self.detach_node()
            self._node_weak_ref = weakref.ref(node)
            if not node.has_parameter(USE_SIM_TIME_NAME):
                node.declare_parameter(USE_SIM_TIME_NAME, False)
            param = node.get_parameter(USE_SIM_TIME_NAME)
            if param.type_ == Parameter.Type.BOOL:
                self.ros_time_is_active = param.value
            elif param.type_ != Parameter.Type.NOT_SET:
                node.get_logger().error(
                    f"Invalid type for parameter '{USE_SIM_TIME_NAME}' {param.type_!r}: "
                    'should be bool'
                )
            node.add_on_set_parameters_callback(self._on_parameters)

    def detach_node(self) -> None:
        """Stop following the node (its `/clock` subscription goes too)."""
        with self._lock:
            node = self._get_node()
            self._unsubscribe()
            if node is not None:
                # (a destroyed node's parameters may be gone already)
                with contextlib.suppress(ValueError):
                    node.remove_on_set_parameters_callback(self._on_parameters)
            self._node_weak_ref = None

    def _on_parameters(self, parameters: list[Parameter]) -> SetParametersResult:

        for param in parameters:
            if param.name != USE_SIM_TIME_NAME:
                continue
            if param.type_ == Parameter.Type.BOOL:
                self.ros_time_is_active = param.value
            elif param.type_ != Parameter.Type.NOT_SET:
                return result(
                    False, f'{USE_SIM_TIME_NAME} parameter set to something besides a bool'
                )
        return result(True)

    # -- clocks -------------------------------------------------------------------------------
    def attach_clock(self, clock: ROSClock) -> None:
        """Drive `clock` (a ROS clock) from now on; it takes the newest `/clock` time."""
        if not isinstance(clock, ROSClock) or clock.clock_type != ClockType.ROS_TIME:
            raise ValueError('Only clocks with type ROS_TIME can be attached.')
        with self._lock:
            if self._last_time_set is not None:
                clock.set_ros_time_override(self._last_time_set)
            clock.set_ros_time_is_active(self._ros_time_is_active)
            self._associated_clocks.append(clock)

    def destroy(self) -> None:
        """Detach from the node and forget the clocks."""
        self.detach_node()
        with self._lock:
            self._associated_clocks.clear()
