"""One process context: the Zenoh session, the entity-id counter, shutdown.

rmw_zenoh numbers nodes and endpoints from one counter per context and keys the graph by
(session id, node id), so both live here. The work queue does not: each executor owns the work
of its nodes (see ros2lite.executors); the context only wakes executors when it shuts down.
"""

from __future__ import annotations

import atexit
import contextlib
import itertools
import os
import signal
import sys
import threading
import weakref
from collections.abc import Callable
from types import FrameType
from typing import TYPE_CHECKING, Any

from ros2lite.arguments import RosArgs, parse_ros_args
from ros2lite.exceptions import NotInitializedException

if TYPE_CHECKING:
    from ros2lite.executors import Executor
    from ros2lite.graph import GraphCache
    from ros2lite.node import Node
    from ros2lite.service import Service
    from ros2lite.transport.handles import Session


class Context:
    """Owns the session; nodes, endpoints and executors of a process share it."""

    def __init__(self) -> None:
        self.session: Session | None = None
        self.domain_id = 0
        self.zid = ''
        self.router: str | None = None
        # the enclave named by `--ros-args --enclave` ('/' if none), announced in every token
        self.enclave = '/'
        self.args = RosArgs()
        self.argv: list[str] = []
        # executors of this context, woken when it shuts down or is told to terminate
        self._executors: weakref.WeakSet[Executor] = weakref.WeakSet()
        # service servers of this process by key, so a blocking call can tell when waiting
        # for one of them would deadlock
        self.local_services: dict[str, Service[Any, Any]] = {}
        self._ids = itertools.count()
        self._lock = threading.Lock()
        self._nodes: list[Node] = []
        self._on_shutdown: list[Callable[[], object]] = []
        self._graph: GraphCache | None = None
        # set by SIGTERM: ok() turns False at once and spinning executors raise
        # ExternalShutdownException; the session itself closes on the way out
        self.terminating = False

    def init(
        self,
        args: list[str] | None = None,
        *,
        router: str | None = None,
        domain_id: int | None = None,
        short_lived: bool = False,
        autostart: bool = True,
    ) -> Context:
        """Open the session; `args=None` means `sys.argv`, as rclpy.init does, so
        `--ros-args` given to a node's process reach its nodes. `short_lived` (tools: CLI
        verbs) opens a client session that fails fast without a router, instead of a
        node's; such a tool starts the daemon only with `autostart`
        (see :func:`ros2lite.daemon.connect.connect`)."""
        from ros2lite.daemon.connect import connect
        from ros2lite.transport.config import domain_id as env_domain_id

        if self.session is not None:
            raise RuntimeError('Context.init() must only be called once')
        self.terminating = False
        self.argv = list(sys.argv if args is None else args)
        self.args = parse_ros_args(self.argv)
        if self.args.enclave is not None:
            from ros2lite.security.environment import use_enclave

            use_enclave(self.args.enclave)  # the security material this process loads
        self.enclave = self.args.enclave or '/'
        self.domain_id = env_domain_id() if domain_id is None else domain_id
        self.router = router
        self.session = connect(router, tool=short_lived, autostart=autostart)
        self.zid = str(self.session.info.zid())
        _live.add(self)
        return self

    # `with ros2lite.init():` shuts the context down on the way out, as rclpy allows
    def __enter__(self) -> Context:
        return self

    def __exit__(self, *exc: object) -> None:
        self.try_shutdown()

    def ok(self) -> bool:
        """Whether the session is open and no SIGTERM asked it to stop."""
        return self.session is not None and not self.terminating

    def require(self) -> Session:
        """The session; NotInitializedException before init()."""
        if self.session is None:
            raise NotInitializedException()
        return self.session

    def next_entity_id(self) -> int:
        """A fresh id for a node or endpoint (rmw_zenoh numbers both from one counter)."""
        with self._lock:
            return next(self._ids)

    @property
    def graph(self) -> GraphCache:
        """The live graph cache, created on first use (CLI snapshots don't need it)."""
        with self._lock:
            if self._graph is None:
                from ros2lite.graph import GraphCache

                self._graph = GraphCache(self.require(), self.domain_id)
            return self._graph

    def add_node(self, node: Node) -> None:
        """Remember a node, to destroy it at shutdown."""
        with self._lock:
            self._nodes.append(node)

    def remove_node(self, node: Node) -> None:
        """Forget a destroyed node."""
        with self._lock:
            if node in self._nodes:
                self._nodes.remove(node)

    def on_shutdown(self, fn: Callable[[], object]) -> None:
        """Call `fn()` when the context shuts down."""
        self._on_shutdown.append(fn)

    def add_executor(self, executor: Executor) -> None:
        """Remember an executor, to wake it at shutdown."""
        self._executors.add(executor)

    def wake(self) -> None:
        """Wake every executor of this context (it looks at ok() again)."""
        for executor in list(self._executors):
            executor.wake()

    def shutdown(self) -> None:
        """Destroy the nodes, close the session and wake the executors."""
        if self.session is None:
            return
        for fn in self._on_shutdown:
            fn()
        for node in list(self._nodes):
            node.destroy_node()
        if self._graph is not None:
            self._graph.close()
            self._graph = None
        session, self.session = self.session, None
        try:
            session.close()
        finally:
            self.wake()
            self._ids = itertools.count()

    def try_shutdown(self) -> None:
        """shutdown() unless already shut down."""
        if self.session is not None:
            self.shutdown()

    def _terminate(self) -> None:
        self.terminating = True
        self.wake()


# Contexts still open at interpreter exit are shut down first: zenoh threads and our pump
# threads must be gone before Python finalises, or the process aborts instead of exiting.
_live: weakref.WeakSet[Context] = weakref.WeakSet()


@atexit.register
def _shutdown_live_contexts() -> None:
    for ctx in list(_live):
        with contextlib.suppress(Exception):
            ctx.try_shutdown()


# Zenoh runs each callback handler (a service's queryable, a query's replies) on a non-daemon
# Python thread that lives as long as the handler: Python joins those before atexit runs, so
# the sessions must close earlier, where concurrent.futures also hooks in.
_register_early = getattr(threading, '_register_atexit', None)
if _register_early is not None:
    _register_early(_shutdown_live_contexts)


_previous_sigterm: Callable[[int, FrameType | None], object] | int | signal.Handlers | None = (
    signal.SIG_DFL
)


def _on_sigterm(signum: int, frame: FrameType | None) -> None:
    """SIGTERM as rclpy handles it: open contexts stop being ok() and spinning executors
    raise ExternalShutdownException, so `main()` can leave through its normal clean-up.
    Doing the shutdown itself here could interrupt a zenoh call on this very thread."""
    open_contexts = [ctx for ctx in list(_live) if ctx.ok()]
    for ctx in open_contexts:
        ctx._terminate()
    if callable(_previous_sigterm):
        _previous_sigterm(signum, frame)
    elif not open_contexts and _previous_sigterm == signal.SIG_DFL:
        # nothing of ours to stop: die of the signal as if we had never been installed
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        os.kill(os.getpid(), signal.SIGTERM)


def install_signal_handlers() -> None:
    """Route SIGTERM through `_on_sigterm` (main thread only; a handler already there is
    still called after ours)."""
    global _previous_sigterm
    if threading.current_thread() is not threading.main_thread():
        return
    current = signal.getsignal(signal.SIGTERM)
    if current is _on_sigterm:
        return
    _previous_sigterm = current
    signal.signal(signal.SIGTERM, _on_sigterm)


_default = Context()


def default_context() -> Context:
    """The process' context (the one `ros2lite.init()` opens)."""
    return _default
