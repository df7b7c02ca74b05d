"""ParameterEventHandler (rclpy's): callbacks for changes of other nodes' parameters, from
`/parameter_events`.

`add_parameter_callback(name, node, cb)` calls `cb(parameter_msg)` when that node's parameter
is declared or changed; `add_parameter_event_callback(cb)` gets every ParameterEvent. The
newest callback runs first, as in rclpy.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from itertools import chain
from typing import TYPE_CHECKING

from ros2lite.parameters.events import TOPIC, TYPE
from ros2lite.qos import QoSProfile, qos_profile_parameter_events

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.event_handler import SubscriptionEventCallbacks
    from ros2lite.msgs.rcl_interfaces.msg import Parameter as ParameterMsg
    from ros2lite.msgs.rcl_interfaces.msg import ParameterEvent
    from ros2lite.node import Node
    from ros2lite.qos_overriding_options import QoSOverridingOptions

# what the two kinds of callback get
ParameterCallback = Callable[['ParameterMsg'], object]
ParameterEventCallback = Callable[['ParameterEvent'], object]

__all__ = ['ParameterCallbackHandle', 'ParameterEventCallbackHandle', 'ParameterEventHandler']


class ParameterCallbackHandle:
    """One registered parameter callback (give it back to remove it)."""

    def __init__(self, parameter_name: str, node_name: str, callback: ParameterCallback) -> None:
        self.parameter_name = parameter_name
        self.node_name = node_name
        self.callback = callback


class ParameterEventCallbackHandle:
    """One registered event callback (give it back to remove it)."""

    def __init__(self, callback: ParameterEventCallback) -> None:
        self.callback = callback


class ParameterEventHandler:
    """Watches /parameter_events on `node` and dispatches to the registered callbacks."""

    class Callbacks:
        """The registered callbacks, and their dispatch of one event."""

        def __init__(self) -> None:
            self.parameter_callbacks: dict[tuple[str, str], list[ParameterCallbackHandle]] = {}
            self.event_callbacks: list[ParameterEventCallbackHandle] = []
            self._lock = threading.RLock()

        def event_callback(self, event: ParameterEvent) -> None:
            """Dispatch one event: parameter callbacks first, newest first, then event ones."""
            with self._lock:
                parameter_callbacks = {k: list(v) for k, v in self.parameter_callbacks.items()}
                event_callbacks = list(self.event_callbacks)
            for (parameter_name, node_name), handles in parameter_callbacks.items():
                parameter = ParameterEventHandler.get_parameter_from_event(
                    event, parameter_name, node_name
                )
                if parameter is not None:
                    for handle in handles:
                        handle.callback(parameter)
            for event_handle in event_callbacks:
                event_handle.callback(event)

        def add_parameter_callback(
            self, parameter_name: str, node_name: str, callback: ParameterCallback
        ) -> ParameterCallbackHandle:
            """Register `callback` for one parameter of one node (it runs before older ones)."""
            handle = ParameterCallbackHandle(parameter_name, node_name, callback)
            with self._lock:
                self.parameter_callbacks.setdefault((parameter_name, node_name), []).insert(
                    0, handle
                )
            return handle

        def remove_parameter_callback(self, handle: ParameterCallbackHandle) -> None:
            """Forget a parameter callback; RuntimeError if it is not registered."""
            key = (handle.parameter_name, handle.node_name)
            with self._lock:
                handles = self.parameter_callbacks.get(key)
                if not handles or handle not in handles:
                    raise RuntimeError("Callback doesn't exist")
                handles.remove(handle)
                if not handles:
                    del self.parameter_callbacks[key]

        def add_parameter_event_callback(
            self, callback: ParameterEventCallback
        ) -> ParameterEventCallbackHandle:
            """Register `callback` for every event (it runs before older ones)."""
            handle = ParameterEventCallbackHandle(callback)
            with self._lock:
                self.event_callbacks.insert(0, handle)
            return handle

        def remove_parameter_event_callback(self, handle: ParameterEventCallbackHandle) -> None:
            """Forget an event callback; RuntimeError if it is not registered."""
            with self._lock:
                if handle not in self.event_callbacks:
                    raise RuntimeError("Callback doesn't exist")
                self.event_callbacks.remove(handle)

    def __init__(
        self,
        node: Node,
        qos_profile: QoSProfile = qos_profile_parameter_events,
        callback_group: CallbackGroup | None = None,
        event_callbacks: SubscriptionEventCallbacks | None = None,
        qos_overriding_options: QoSOverridingOptions | None = None,
        raw: bool = False,
    ) -> None:
        """rclpy's arguments; `event_callbacks`, `qos_overriding_options` and `raw` are
        accepted and not used (the subscription is a plain typed one)."""
        self.node = node
        self.qos_profile = qos_profile
        self._callbacks = ParameterEventHandler.Callbacks()
        self.parameter_event_subscription = node.create_subscription(
            TYPE,
            TOPIC,
            self._callbacks.event_callback,
            qos_profile,
            callback_group=callback_group,
        )

    def destroy(self) -> None:
        """Stop watching /parameter_events."""
        self.node.destroy_subscription(self.parameter_event_subscription)

    def add_parameter_callback(
        self, parameter_name: str, node_name: str, callback: ParameterCallback
    ) -> ParameterCallbackHandle:
        """Call `callback(parameter)` when `node_name`'s `parameter_name` is set (a relative
        node name is in this node's namespace)."""
        return self._callbacks.add_parameter_callback(
            parameter_name, self._resolve_path(node_name), callback
        )

    def remove_parameter_callback(self, handle: ParameterCallbackHandle) -> None:
        """Forget a parameter callback; RuntimeError if it is not registered."""
        self._callbacks.remove_parameter_callback(handle)

    def add_parameter_event_callback(
        self, callback: ParameterEventCallback
    ) -> ParameterEventCallbackHandle:
        """Call `callback(event)` for every ParameterEvent."""
        return self._callbacks.add_parameter_event_callback(callback)

    def remove_parameter_event_callback(self, handle: ParameterEventCallbackHandle) -> None:
        """Forget an event callback; RuntimeError if it is not registered."""
        self._callbacks.remove_parameter_event_callback(handle)

    @staticmethod
    def get_parameter_from_event(
        event: ParameterEvent, parameter_name: str, node_name: str
    ) -> ParameterMsg | None:
        """The new or changed `parameter_name` of `node_name` in `event`, or None."""
        if event.node != node_name:
            return None
        for parameter in chain(event.new_parameters, event.changed_parameters):
            if parameter.name == parameter_name:
                return parameter
        return None

    @staticmethod
    def get_parameters_from_event(event: ParameterEvent) -> list[ParameterMsg]:
        """Every new or changed parameter in `event`."""
        return [*event.new_parameters, *event.changed_parameters]

    def _resolve_path(self, node_path: str | None = None) -> str:
        """A node name made absolute against this node (None: this node)."""
        if not node_path:
            return str(self.node.get_fully_qualified_name())
        if node_path.startswith('/'):
            return node_path
        namespace = self.node.get_namespace().rstrip('/')
        return f'{namespace}/{node_path}'
