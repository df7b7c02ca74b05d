"""One process context: the Zenoh session, the entity-id counter, shutdown.

rmw_zenoh numbers nodes and endpoints from one counter per context and keys the graph by
(session id, node id), so both live here. The work queue does not: each executor owns the work
of its nodes (see ros2lite.executors); the context only wakes executors when it shuts down.
"""

from __future__ import annotations

import atexit
import contextlib
import itertools
import sys
import threading
import weakref
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Protocol

from ros2lite.exceptions import NotInitializedException, Ros2liteError
from ros2lite.runtime.arguments import RosArgs, parse_ros_args

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.graph import GraphCache
    from ros2lite.transport.handles import Session


# The context sits below the nodes, executors and services that register with it: it knows
# them only by what it (or a blocking client) asks of them.


class CountingPublisher(Protocol):
    """A node's publisher as the context sees it: how many messages it has sent."""

    @property
    def sent(self) -> int:
        """Messages published so far."""
        ...


class ContextNode(Protocol):
    """A node of the context (:class:`ros2lite.node.Node`): destroyed when it shuts down."""

    @property
    def publishers(self) -> Sequence[CountingPublisher]:
        """Its publishers (counted across a router outage)."""
        ...

    def destroy_node(self) -> None:
        """Leave the graph: every entity of the node goes."""
        ...


class ContextExecutor(Protocol):
    """An executor of the context (:class:`ros2lite.executors.Executor`): woken when it shuts
    down or is told to terminate."""

    def wake(self) -> None:
        """Any thread: make a waiting spin look again (at ok())."""
        ...


class LocalService(Protocol):
    """A service server of this process (:class:`ros2lite.service.Service`), as a client
    calling it from a callback looks at it to tell a deadlock coming."""

    def runs_on(self, executor: object) -> bool:
        """Whether the node serving it is attached to `executor` (which then runs the
        server's callbacks)."""
        ...

    @property
    def callback_group(self) -> CallbackGroup:
        """The group the server's callback runs in."""
        ...


class InvalidDomainIdError(Ros2liteError, RuntimeError):
    """A domain id outside what ROS allows."""


class Context:
    """Owns the session; nodes, endpoints and executors of a process share it."""

    def __init__(self) -> None:
        self.session: Session | None = None
        self.domain_id = 0
        self.zid = ''
        self.router: str | None = None
        # the enclave announced in every token: `--ros-args --enclave` ('/' if none), or
        # the one whose certificate a secured process shows (security.announced_enclave)
        self.enclave = '/'
        self.args = RosArgs()
        self.argv: list[str] = []
        # executors of this context, woken when it shuts down or is told to terminate
        self._executors: weakref.WeakSet[ContextExecutor] = weakref.WeakSet()
        # service servers of this process by key, so a blocking call can tell when waiting
        # for one of them would deadlock
        self.local_services: dict[str, LocalService] = {}
        self._ids = itertools.count()
        self._lock = threading.Lock()
        self._nodes: list[ContextNode] = []
        self._on_shutdown: list[Callable[[], object]] = []
        self._graph: GraphCache | None = None
        # held for the whole of a shutdown: ok() turns False as it begins, so whoever waits
        # for it to end (a second caller, the interpreter's exit) needs more than ok()
        self._shutdown_lock = threading.RLock()
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
        from ros2lite.transport.endpoints import domain_id as env_domain_id

        if self.session is not None:
            raise RuntimeError('Context.init() must only be called once')
        if domain_id is not None and (not isinstance(domain_id, int) or domain_id < 0):
            raise InvalidDomainIdError(f'invalid domain id {domain_id!r}: it must not be negative')
        self.terminating = False
        argv = list(sys.argv if args is None else args)
        for arg in argv:
            arg.encode('utf-8')  # rcl takes C strings: undecodable arguments fail here, as there
        self.argv = argv
        self.args = parse_ros_args(self.argv)
        if self.args.stdout_logs is not None:
            from ros2lite.logging import set_console_output

            set_console_output(self.args.stdout_logs)
        from ros2lite.security.environment import announced_enclave, use_enclave

        if self.args.enclave is not None:
            use_enclave(self.args.enclave)  # the security material this process loads
        self.enclave = announced_enclave(self.args.enclave)
        self.domain_id = env_domain_id() if domain_id is None else domain_id
        self.router = router
        if not short_lived:  # a node: large messages reuse freed buffers (ros2lite.runtime.memory)
            from ros2lite.runtime.memory import keep_large_buffers

            keep_large_buffers()
        self.session = connect(router, tool=short_lived, autostart=autostart)
        self.zid = str(self.session.info.zid())
        _live.add(self)
        if not short_lived:
            self._watch_client_link(router)
        return self

    def published(self) -> int:
        """Messages this context's nodes have published so far (their publishers' now)."""
        with self._lock:
            nodes = list(self._nodes)
        return sum(pub.sent for node in nodes for pub in list(node.publishers))

    def _watch_client_link(self, router: str | None) -> None:
        """A node whose session is a client (secured nodes are) loses what is published
        while its router is away: say so when the link drops, and when it is back."""
        from ros2lite.daemon.connect import node_is_client
        from ros2lite.logging import get_logger

        client, endpoint = node_is_client(router)
        if not client:
            return
        logger = get_logger('rmw_zenoh_cpp')
        stop = threading.Event()
        sent_at_loss = [0]

        def changed(linked: bool) -> None:
            if stop.is_set():
                return  # shutting down: the session closes, the router is not gone
            if linked:
                lost = self.published() - sent_at_loss[0]
                logger.warning(
                    f'The link to the Zenoh router at {endpoint} is back; {lost} message(s) '
                    "this process published while it was away reached no one"
                )
            else:
                sent_at_loss[0] = self.published()
                logger.warning(
                    f'Lost the link to the Zenoh router at {endpoint}: this node is a Zenoh '
                    'client, so what is published until it is back neither reaches it nor '
                    'leaves it'
                )

        def watch() -> None:
            link = RouterLink(self, changed)
            while not stop.wait(_LINK_CHECK_PERIOD):
                link.check()

        thread = threading.Thread(target=watch, name='router-link', daemon=True)

        def end() -> None:  # before the session closes: no thread of ours left inside zenoh
            stop.set()
            if thread is not threading.current_thread():
                thread.join()

        self.on_shutdown(end)
        thread.start()

    # `with Context():` initialises it (as rclpy's does) and `with ros2lite.init():` uses the
    # one just initialised; both shut it down on the way out
    def __enter__(self) -> Context:
        if self.session is None:
            self.init()
        return self

    def __exit__(self, *exc: object) -> None:
        self.try_shutdown()

    def ok(self) -> bool:
        """Whether the session is open and no SIGTERM asked it to stop."""
        return self.session is not None and not self.terminating

    def get_domain_id(self) -> int:
        """The ROS domain of this context (rclpy's accessor)."""
        self.require()
        return self.domain_id

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

    def graph_changed_locally(self, token_key: str, alive: bool) -> None:
        """An entity of this process appeared or went: the graph cache (if one is kept)
        learns it now, not when the liveliness subscription reports it back."""
        graph = self._graph
        if graph is not None:
            graph.token_changed(token_key, alive)

    def add_node(self, node: ContextNode) -> None:
        """Remember a node, to destroy it at shutdown."""
        with self._lock:
            self._nodes.append(node)

    def remove_node(self, node: ContextNode) -> None:
        """Forget a destroyed node."""
        with self._lock:
            if node in self._nodes:
                self._nodes.remove(node)

    def on_shutdown(self, fn: Callable[[], object]) -> None:
        """Call `fn()` when this context shuts down."""
        with self._lock:
            self._on_shutdown.append(fn)

    def remove_on_shutdown(self, fn: Callable[[], object]) -> None:
        """Forget a callback given to :meth:`on_shutdown` (a sleeper that woke up)."""
        with self._lock:
            if fn in self._on_shutdown:
                self._on_shutdown.remove(fn)

    def add_executor(self, executor: ContextExecutor) -> None:
        """Remember an executor, to wake it at shutdown."""
        self._executors.add(executor)

    def wake(self) -> None:
        """Wake every executor of this context (it looks at ok() again)."""
        for executor in list(self._executors):
            executor.wake()

    def shutdown(self) -> None:
        """Destroy the nodes, close the session and wake the executors; a context that is
        not initialised cannot be shut down (RuntimeError, as in rclpy; :meth:`try_shutdown`
        does not mind)."""
        with self._shutdown_lock:
            if self.session is None:
                raise RuntimeError('Context must be initialized before it can be shutdown')
            with self._lock:
                callbacks, self._on_shutdown = self._on_shutdown, []
            for fn in callbacks:
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
                from ros2lite.transport.shm import forget

                forget(session)  # its shared-memory pool goes with it, even if close failed
                # and the last reference goes here, under the lock: zenoh lets go of the GIL
                # while it drops a session, and a thread that is still inside zenoh when
                # the interpreter finalises aborts the process
                del session
                self.wake()
                self._ids = itertools.count()

    def try_shutdown(self) -> None:
        """shutdown() unless already shut down (or once a shutdown under way on another thread
        has finished)."""
        with self._shutdown_lock:
            if self.session is not None:
                self.shutdown()

    def destroy(self) -> None:
        """Release the context for good (rclpy's); shuts it down first if it still runs."""
        self.try_shutdown()

    def terminate(self) -> None:
        """SIGINT/SIGTERM (signals.py): stop being ok() and wake the spinning executors,
        leaving the shutdown itself to the program's clean-up."""
        self.terminating = True
        self.wake()

    def shutdown_at_exit(self, wait: float) -> None:
        """try_shutdown() at interpreter exit, unless a shutdown under way on another
        thread holds on longer than `wait` seconds (errors are of no use any more)."""
        if not self._shutdown_lock.acquire(timeout=wait):
            return
        try:
            with contextlib.suppress(Exception):
                self.try_shutdown()
        finally:
            self._shutdown_lock.release()


class RouterLink:
    """Tells, once per change, whether a context's session still reaches a router: a tool's
    client session hears nothing while its router is away, a node's peers only what they
    already met, and neither may let that pass in silence."""

    def __init__(self, context: Context, on_change: Callable[[bool], object]) -> None:
        self.context = context
        self.on_change = on_change
        self.linked = True  # as far as we know: a session opens with its router

    def check(self) -> None:
        """Look now; call ``on_change(linked)`` if it differs from the last look."""
        session = self.context.session
        if session is None:
            return
        from ros2lite.transport.open import router_connected

        linked = router_connected(session)
        if linked != self.linked:
            self.linked = linked
            self.on_change(linked)


# how often a client node's session is looked at for its router link (seconds)
_LINK_CHECK_PERIOD = 0.25

# Contexts still open at interpreter exit are shut down first: zenoh threads and our pump
# threads must be gone before Python finalises, or the process aborts instead of exiting.
_live: weakref.WeakSet[Context] = weakref.WeakSet()
# how long the interpreter's exit waits for a shutdown under way on another thread
_EXIT_WAIT = 10.0


def open_contexts() -> list[Context]:
    """This process' contexts that are still ok() (what SIGINT and SIGTERM stop)."""
    return [ctx for ctx in list(_live) if ctx.ok()]


@atexit.register
def _shutdown_live_contexts() -> None:
    for ctx in list(_live):
        # a shutdown() called from a daemon thread (say, on end of input) lets the main
        # thread's spin return and the program end while the session is still closing;
        # Python would stop that thread inside zenoh and abort the process: let it finish
        ctx.shutdown_at_exit(_EXIT_WAIT)


# Zenoh runs each callback handler (a service's queryable, a query's replies) on a non-daemon
# Python thread that lives as long as the handler: Python joins those before atexit runs, so
# the sessions must close earlier, where concurrent.futures also hooks in.
_register_early = getattr(threading, '_register_atexit', None)
if _register_early is not None:
    _register_early(_shutdown_live_contexts)


_default = Context()


def default_context() -> Context:
    """The process' context (the one `ros2lite.init()` opens)."""
    return _default
