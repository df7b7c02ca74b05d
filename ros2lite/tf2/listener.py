"""The listener: fills a buffer from `/tf` and `/tf_static` (tf2_ros's TransformListener)."""

from __future__ import annotations

import contextlib
import secrets
import threading
from typing import TYPE_CHECKING

from ros2lite.callback_groups import ReentrantCallbackGroup
from ros2lite.executors import ExternalShutdownException, SingleThreadedExecutor
from ros2lite.msgs.tf2_msgs.msg import TFMessage
from ros2lite.node import Node
from ros2lite.qos import QoSProfile
from ros2lite.tf2.qos import (
    TF_STATIC_TOPIC,
    TF_TOPIC,
    dynamic_listener_qos,
    static_listener_qos,
)

if TYPE_CHECKING:
    from ros2lite.tf2.core import BufferCore

__all__ = ['TransformListener']

_AUTHORITY = 'default_authority'


class TransformListener:
    """Subscribes `node` to `/tf` and `/tf_static` and stores what arrives in `buffer`.

    The subscriptions sit in a reentrant callback group, so a callback of the node may wait
    for a transform while another thread of a multi-threaded executor delivers it. With
    `spin_thread`, a private node spun by a thread of its own listens instead (as rclcpp's
    listener does), so the buffer fills even while the caller's node is busy or not spun.
    """

    def __init__(
        self,
        buffer: BufferCore,
        node: Node,
        *,
        spin_thread: bool = False,
        qos: QoSProfile | int | None = None,
        static_qos: QoSProfile | int | None = None,
    ) -> None:
        self.buffer = buffer
        self.node = node
        self.executor: SingleThreadedExecutor | None = None
        self.dedicated_listener_thread: threading.Thread | None = None
        listening = node
        if spin_thread:
            listening = Node(
                f'transform_listener_impl_{secrets.token_hex(6)}',
                context=node.context,
                start_parameter_services=False,
            )
        self._listening = listening
        self.group = ReentrantCallbackGroup()
        self.tf_sub = listening.create_subscription(
            TFMessage,
            TF_TOPIC,
            self.callback,
            dynamic_listener_qos() if qos is None else qos,
            callback_group=self.group,
        )
        self.tf_static_sub = listening.create_subscription(
            TFMessage,
            TF_STATIC_TOPIC,
            self.static_callback,
            static_listener_qos() if static_qos is None else static_qos,
            callback_group=self.group,
        )
        if spin_thread:
            self.executor = SingleThreadedExecutor(context=node.context)
            self.executor.add_node(listening)
            self.dedicated_listener_thread = threading.Thread(
                target=self._spin, name='tf2_listener', daemon=True
            )
            self.dedicated_listener_thread.start()

    def _spin(self) -> None:
        assert self.executor is not None
        with contextlib.suppress(ExternalShutdownException):
            self.executor.spin()

    def callback(self, data: TFMessage) -> None:
        """Store the transforms of moving frames."""
        store = self.buffer.set_transform
        for transform in data.transforms:
            store(transform, _AUTHORITY)

    def static_callback(self, data: TFMessage) -> None:
        """Store the transforms of fixed frames."""
        store = self.buffer.set_transform_static
        for transform in data.transforms:
            store(transform, _AUTHORITY)

    def unregister(self) -> None:
        """Stop listening (and stop the private thread, if any)."""
        if self.executor is not None:
            self.executor.shutdown()
            if self.dedicated_listener_thread is not None:
                self.dedicated_listener_thread.join(5)
            self.executor = None
        if self._listening is not self.node:
            self._listening.destroy_node()
        else:
            self.node.destroy_subscription(self.tf_sub)
            self.node.destroy_subscription(self.tf_static_sub)
