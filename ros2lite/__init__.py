"""ros2lite: the ROS 2 command line and a small rclpy-like client library over rmw_zenoh.

Names are re-exported lazily so `import ros2lite` (and `ros2lite --help`) stays cheap:

    import ros2lite
    from ros2lite.msgs.std_msgs.msg import String
    ros2lite.init()
    node = ros2lite.Node('talker')
    pub = node.create_publisher(String, 'chatter', 10)
"""

from __future__ import annotations

import importlib
from typing import Any

__version__ = '0.1.0'

_EXPORTS = {
    'Node': 'ros2lite.node', 'Parameter': 'ros2lite.node',
    'Context': 'ros2lite.context', 'default_context': 'ros2lite.context',
    'SingleThreadedExecutor': 'ros2lite.executor', 'Future': 'ros2lite.executor',
    'ExternalShutdownException': 'ros2lite.executor',
    'spin': 'ros2lite.executor', 'spin_once': 'ros2lite.executor',
    'spin_until_future_complete': 'ros2lite.executor',
    'QoSProfile': 'ros2lite.transport.qos', 'ReliabilityPolicy': 'ros2lite.transport.qos',
    'DurabilityPolicy': 'ros2lite.transport.qos', 'HistoryPolicy': 'ros2lite.transport.qos',
    'qos_profile_sensor_data': 'ros2lite.transport.qos',
    'qos_profile_system_default': 'ros2lite.transport.qos',
    'Time': 'ros2lite.clock', 'Duration': 'ros2lite.duration', 'Clock': 'ros2lite.clock',
    'get_logger': 'ros2lite.logging', 'MessageInfo': 'ros2lite.subscription',
}


def init(args: list[str] | None = None, *, context: Any = None, router: str | None = None,
         domain_id: int | None = None) -> Any:
    """Open the node's Zenoh session (a peer; with no router it starts the daemon, or runs on
    without one: see `ros2lite.daemon.connect`).

    `args=None` reads `sys.argv` like rclpy; the returned context also works as
    `with ros2lite.init(): …`, shutting down on exit. Like rclpy it installs a SIGTERM
    handler: spinning then ends with ExternalShutdownException and `ok()` turns False.
    """
    from ros2lite.context import default_context, install_signal_handlers
    ctx = (context or default_context()).init(args, router=router, domain_id=domain_id)
    install_signal_handlers()
    return ctx


def shutdown(*, context: Any = None) -> None:
    from ros2lite.context import default_context
    (context or default_context()).shutdown()


def try_shutdown(*, context: Any = None) -> None:
    from ros2lite.context import default_context
    (context or default_context()).try_shutdown()


def ok(*, context: Any = None) -> bool:
    from ros2lite.context import default_context
    return (context or default_context()).ok()


def create_node(node_name: str, **kwargs: Any) -> Any:
    from ros2lite.node import Node
    return Node(node_name, **kwargs)


def __getattr__(name: str) -> Any:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'ros2lite' has no attribute '{name}'")
    return getattr(importlib.import_module(module), name)
