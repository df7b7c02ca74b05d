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
import threading
import weakref
from collections.abc import Callable
from typing import TYPE_CHECKING

__version__ = '0.1.0'

if TYPE_CHECKING:  # what type checkers see; at run time the names load lazily
    from typing_extensions import Unpack

    from ros2lite.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
    from ros2lite.clock import Clock
    from ros2lite.context import Context, default_context
    from ros2lite.duration import Duration
    from ros2lite.executors import (
        Executor,
        ExternalShutdownException,
        MultiThreadedExecutor,
        SingleThreadedExecutor,
    )
    from ros2lite.logging import get_logger
    from ros2lite.message_info import MessageInfo
    from ros2lite.node import Node
    from ros2lite.node_options import NodeOptions
    from ros2lite.parameter import Parameter
    from ros2lite.qos import (
        DurabilityPolicy,
        HistoryPolicy,
        QoSProfile,
        ReliabilityPolicy,
        qos_profile_sensor_data,
        qos_profile_system_default,
    )
    from ros2lite.signals import SignalHandlerOptions
    from ros2lite.task import Future, Task
    from ros2lite.time import Time

__all__ = [
    'Clock',
    'Context',
    'DurabilityPolicy',
    'Duration',
    'Executor',
    'ExternalShutdownException',
    'Future',
    'HistoryPolicy',
    'MessageInfo',
    'MultiThreadedExecutor',
    'MutuallyExclusiveCallbackGroup',
    'Node',
    'Parameter',
    'QoSProfile',
    'ReentrantCallbackGroup',
    'ReliabilityPolicy',
    'SingleThreadedExecutor',
    'Task',
    'Time',
    '__version__',
    'create_node',
    'default_context',
    'get_global_executor',
    'get_logger',
    'init',
    'ok',
    'qos_profile_sensor_data',
    'qos_profile_system_default',
    'shutdown',
    'spin',
    'spin_once',
    'spin_until_future_complete',
    'try_shutdown',
]

_EXPORTS = {
    'Node': 'ros2lite.node',
    'Parameter': 'ros2lite.parameter',
    'Context': 'ros2lite.context',
    'default_context': 'ros2lite.context',
    'Executor': 'ros2lite.executors',
    'SingleThreadedExecutor': 'ros2lite.executors',
    'MultiThreadedExecutor': 'ros2lite.executors',
    'ExternalShutdownException': 'ros2lite.executors',
    'Future': 'ros2lite.task',
    'Task': 'ros2lite.task',
    'MutuallyExclusiveCallbackGroup': 'ros2lite.callback_groups',
    'ReentrantCallbackGroup': 'ros2lite.callback_groups',
    'QoSProfile': 'ros2lite.qos',
    'ReliabilityPolicy': 'ros2lite.qos',
    'DurabilityPolicy': 'ros2lite.qos',
    'HistoryPolicy': 'ros2lite.qos',
    'qos_profile_sensor_data': 'ros2lite.qos',
    'qos_profile_system_default': 'ros2lite.qos',
    'Time': 'ros2lite.time',
    'Duration': 'ros2lite.duration',
    'Clock': 'ros2lite.clock',
    'get_logger': 'ros2lite.logging',
    'MessageInfo': 'ros2lite.message_info',
}


def init(
    args: list[str] | None = None,
    *,
    context: Context | None = None,
    router: str | None = None,
    domain_id: int | None = None,
    signal_handler_options: SignalHandlerOptions | None = None,
) -> Context:
    """Open the node's Zenoh session (a peer; with no router it starts the daemon, or runs on
    without one: see `ros2lite.daemon.connect`).

    `args=None` reads `sys.argv` like rclpy; the returned context also works as
    `with ros2lite.init(): …`, shutting down on exit. Like rclpy it installs SIGINT and
    SIGTERM handlers (`signal_handler_options` chooses): `ok()` then turns False, and
    spinning ends (SIGTERM: with ExternalShutdownException; Ctrl-C still raises
    KeyboardInterrupt).
    """
    from ros2lite.context import default_context
    from ros2lite.signals import SignalHandlerOptions, install_signal_handlers

    ctx = (context or default_context()).init(args, router=router, domain_id=domain_id)
    options = SignalHandlerOptions.ALL if signal_handler_options is None else signal_handler_options
    install_signal_handlers(options)
    return ctx


def shutdown(*, context: Context | None = None, uninstall_handlers: bool | None = None) -> None:
    """Close the context's session, so its nodes leave the graph (RuntimeError if it is not
    initialised). Signal handlers are put back when `uninstall_handlers` says so, by default
    when it is the default context."""
    from ros2lite.context import default_context

    ctx = context or default_context()
    ctx.shutdown()
    _after_shutdown(ctx, uninstall_handlers)


def try_shutdown(*, context: Context | None = None, uninstall_handlers: bool | None = None) -> None:
    """:func:`shutdown` if the context is still open (one under way on another thread is
    waited for, not repeated: :meth:`Context.try_shutdown`)."""
    from ros2lite.context import default_context

    ctx = context or default_context()
    ctx.try_shutdown()
    _after_shutdown(ctx, uninstall_handlers)


def _after_shutdown(ctx: Context, uninstall_handlers: bool | None) -> None:
    from ros2lite.context import default_context
    from ros2lite.signals import uninstall_signal_handlers

    if uninstall_handlers or (uninstall_handlers is None and ctx is default_context()):
        uninstall_signal_handlers()


def ok(*, context: Context | None = None) -> bool:
    """Whether the context is open and no SIGTERM asked it to stop."""
    if context is None:  # `while ok(): spin_once(node)` asks this per message: no import
        context = (_default_context or _load_default_context())()
    return context.ok()


_default_context: Callable[[], Context] | None = None


def _load_default_context() -> Callable[[], Context]:
    """ros2lite.context.default_context, imported once (an import per call costs more than
    the call)."""
    global _default_context
    from ros2lite.context import default_context

    _default_context = default_context
    return default_context


def create_node(node_name: str, **kwargs: Unpack[NodeOptions]) -> Node:
    """A Node (rclpy's factory function; the keyword arguments are Node's)."""
    from ros2lite.node import Node

    return Node(node_name, **kwargs)


# -- spinning a node on the context's shared executor (rclpy's global executor), here as in rclpy
_global: weakref.WeakKeyDictionary[Context, SingleThreadedExecutor] = weakref.WeakKeyDictionary()
_global_lock = threading.Lock()
# the last one asked for: `spin_once(node)` in a loop asks every time
_last_global: SingleThreadedExecutor | None = None


def get_global_executor(context: Context | None = None) -> SingleThreadedExecutor:
    """The context's shared single-threaded executor (what ros2lite.spin uses)."""
    global _last_global
    ctx = context or (_default_context or _load_default_context())()
    last = _last_global
    if last is not None and last.context is ctx:
        return last
    from ros2lite.executors import SingleThreadedExecutor

    with _global_lock:
        executor = _global.get(ctx)
        if executor is None:
            executor = _global[ctx] = SingleThreadedExecutor(context=ctx)
        _last_global = executor
        return executor


def spin_once(
    node: Node, *, executor: Executor | None = None, timeout_sec: float | None = None
) -> None:
    """Run one callback of `node` (on the global executor unless one is given)."""
    ex = executor if executor is not None else get_global_executor(node.context)
    added = ex.add_node(node)
    try:
        ex.spin_once(timeout_sec)
    finally:
        if added:
            ex.remove_node(node)


def spin(node: Node, executor: Executor | None = None) -> None:
    """Run the node's callbacks until shutdown (Ctrl-C raises KeyboardInterrupt, as rclpy)."""
    ex = executor if executor is not None else get_global_executor(node.context)
    added = ex.add_node(node)
    try:
        ex.spin()
    finally:
        if added:
            ex.remove_node(node)


def spin_until_future_complete(
    node: Node, future: Future, executor: Executor | None = None, timeout_sec: float | None = None
) -> None:
    """Spin `node` until `future` is done or `timeout_sec` passes."""
    ex = executor if executor is not None else get_global_executor(node.context)
    added = ex.add_node(node)
    try:
        ex.spin_until_future_complete(future, timeout_sec)
    finally:
        if added:
            ex.remove_node(node)


def __getattr__(name: str) -> object:
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'ros2lite' has no attribute '{name}'")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value  # loaded once: `ros2lite.spin_once` in a loop costs no import
    return value
