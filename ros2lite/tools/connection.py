"""A tool's connection to the graph: what a CLI verb, a completion or a script inspecting the
graph needs, in one object.

Graph questions go first to the daemon's graph cache (:mod:`ros2lite.daemon.graph_cache`, as
ros2cli's verbs ask its daemon): no session, no zenoh. When no daemon of ours answers (or
``graph_cache=False``, the CLI's ``--no-daemon``) they are one complete liveliness query of a
session opened on first need: a client session (the daemon started on demand, see
:func:`ros2lite.daemon.connect.connect`), or with ``as_node=True`` a node's peer session.
The connection also makes a hidden node for the tool's publishers and subscriptions, and owns
the executor that runs that node's callbacks, so no caller builds or spins executors itself::

    with Connection() as conn:
        node = conn.node()
        node.create_subscription(String, '/chatter', print, 10)
        conn.spin_until(timeout=5.0)
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable, Iterable
from types import TracebackType
from typing import TYPE_CHECKING

from ros2lite.names import is_hidden_name

if TYPE_CHECKING:  # loaded when a verb needs them: `topic list` only asks the graph
    from ros2lite.context import Context
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.graph import Entity
    from ros2lite.node import Node
    from ros2lite.task import Future
    from ros2lite.timer import Timer

__all__ = ['Connection', 'wait_for_name']

HIDDEN_NODE_PREFIX = '_ros2lite_'
# how often a spinning tool looks whether its router is still there (a SIGKILLed router is
# seen at once: its TCP link closes; a cut network only when zenoh's lease runs out)
ROUTER_CHECK_PERIOD = 0.25


_tool_node_class: type[Node] | None = None


def _tool_node_type() -> type[Node]:
    """The class of a tool's node, made on first use (importing this module loads no node
    code: `topic list` only asks the graph)."""
    global _tool_node_class
    if _tool_node_class is None:
        from ros2lite.node import Node

        class _ToolNode(Node):
            """A tool's node: it reports what it sees its own way, not with rclpy's QoS
            event warnings, and answers graph questions from snapshots, not from a graph
            cache."""

            _default_event_callbacks = False

        _tool_node_class = _ToolNode
    return _tool_node_class


class Connection:
    """One tool run's place on the graph: session, graph snapshots, hidden node, executor."""

    def __init__(
        self,
        *,
        router: str | None = None,
        autostart: bool = True,
        use_sim_time: bool = False,
        as_node: bool = False,
        graph_cache: bool = True,
        on_note: Callable[[str], None] | None = None,
    ) -> None:
        self.router = router
        # where to say what a look at the graph found odd (skipped tokens, a cut answer);
        # each note once per run
        self.on_note = on_note
        self._noted: set[str] = set()
        self.autostart = autostart
        self.graph_cache = graph_cache
        # a node's peer session (a recorder's: it must keep hearing publishers while the
        # router is away) instead of a tool's client session
        self.as_node = as_node
        self.use_sim_time = use_sim_time
        self._context: Context | None = None
        self._node: Node | None = None
        self._executor: SingleThreadedExecutor | None = None
        self._router_watch: Timer | None = None

    @property
    def context(self) -> Context:
        """The context of this run's session (not initialised until something needs it)."""
        if self._context is None:
            from ros2lite.context import Context

            self._context = Context()
        return self._context

    def open(self) -> Connection:
        """Connect (see the module doc) unless already connected; raises a Ros2liteError
        saying why it could not. Whatever needs the session calls this itself."""
        if self.context.session is None:
            self.context.init(
                [], router=self.router, short_lived=not self.as_node, autostart=self.autostart
            )
        return self

    def close(self) -> None:
        """Leave the graph: the node's endpoints and the session go."""
        if self._executor is not None:
            self._executor.shutdown()
            self._executor = None
        if self._context is not None:
            self._context.try_shutdown()

    def __enter__(self) -> Connection:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.close()

    # -- the graph ---------------------------------------------------------------------------
    def entities(self, timeout: float = 5.0) -> list[Entity]:
        """Every entity in the domain: the daemon's graph cache, else one complete query."""
        from ros2lite.graph import read_tokens, survey

        view = None
        if self.graph_cache:
            from ros2lite.daemon.graph_cache import cache_endpoint, cached_keys
            from ros2lite.transport.endpoints import domain_id

            endpoint = cache_endpoint(self.router)
            if endpoint is not None:
                keys = cached_keys(endpoint, domain_id(), min(timeout, 1.0))
                if keys is not None:
                    view = read_tokens(keys)
        if view is None:
            self.open()
            view = survey(self.context.require(), self.context.domain_id, timeout)
        if view.skipped:
            self._note(
                'skipped',
                f"skipped {len(view.skipped)} liveliness token(s) that are not as rmw_zenoh "
                f"makes them, e.g. {view.skipped[0][:200]!a}",
            )
        if not view.complete:
            self._note(
                'cut',
                f"the graph may be incomplete: the router's answer was cut after {timeout:g} s "
                f"({len(view.entities)} entities so far)",
            )
        return view.entities

    def _note(self, kind: str, text: str) -> None:
        if self.on_note is not None and kind not in self._noted:
            self._noted.add(kind)
            self.on_note(text)

    def wait_for_node(self, fqn: str, *, include_hidden: bool, timeout: float) -> bool:
        """Whether the node `fqn` is (or appears within `timeout` s) in the graph; a hidden
        node counts only with `include_hidden`, as ros2cli's node lookups do."""
        from ros2lite.graph import node_full_names

        if is_hidden_name(fqn) and not include_hidden:
            return False
        return wait_for_name(
            lambda: node_full_names(self.entities(), include_hidden=True), fqn, timeout
        )

    # -- the tool's own node -----------------------------------------------------------------
    def node(self, name: str | None = None) -> Node:
        """The hidden node this run uses for its publishers, subscriptions and clients
        (made on first use; `name` only counts then)."""
        if self._node is None:
            from ros2lite.parameter import Parameter

            self.open()
            self._node = _tool_node_type()(
                name or f'{HIDDEN_NODE_PREFIX}{os.getpid()}',
                context=self.context,
                enable_rosout=False,
                use_global_arguments=False,
                start_parameter_services=False,
                parameter_overrides=[
                    Parameter('use_sim_time', value=self.use_sim_time),
                    # a tool's node needs no type description service of its own
                    Parameter('start_type_description_service', value=False),
                ],
            )
        return self._node

    @property
    def executor(self) -> SingleThreadedExecutor:
        """The executor that runs the node's callbacks (on the thread that spins it)."""
        if self._executor is None:
            from ros2lite.executors import SingleThreadedExecutor

            self._executor = SingleThreadedExecutor(context=self.context)
            self._executor.add_node(self.node())
        return self._executor

    def every(self, period: float, callback: Callable[[], object]) -> Timer:
        """Call `callback()` on the executor every `period` s of steady time (reports of a
        tool, which must tick even when sim time stands still)."""
        from ros2lite.clock import Clock, ClockType

        return self.node().create_timer(
            period, callback, clock=Clock(clock_type=ClockType.STEADY_TIME)
        )

    def watch_router(self) -> None:
        """While the tool spins, say when its session loses the router and when it is back:
        a client hears nothing meanwhile.  A node's session (``as_node``: the recorder) keeps
        hearing the peers it met and says so itself."""
        if self._router_watch is not None or self.as_node:
            return
        from ros2lite.context import RouterLink
        from ros2lite.daemon.security import secured_endpoint

        endpoint = secured_endpoint(self.router)
        logger = self.node().get_logger()

        def changed(linked: bool) -> None:
            if linked:
                logger.warn(f'The link to the Zenoh router at {endpoint} is back')
            else:
                logger.warn(
                    f'Lost the link to the Zenoh router at {endpoint}: what is published '
                    'until it is back does not reach this tool'
                )

        self._router_watch = self.every(
            ROUTER_CHECK_PERIOD, RouterLink(self.context, changed).check
        )

    def spin(self) -> None:
        """Run the node's callbacks until the context shuts down (Ctrl-C raises as usual)."""
        self.watch_router()
        self.executor.spin_until(None)

    def spin_until(
        self, condition: Callable[[], bool] | None = None, timeout: float | None = None
    ) -> bool:
        """Run the node's callbacks until `condition()` holds or `timeout` s pass; True when
        the condition ended it."""
        self.watch_router()
        return self.executor.spin_until(condition, timeout)

    def spin_until_future_complete(self, future: Future, timeout: float | None = None) -> None:
        """Run the node's callbacks until `future` is done (or `timeout` s pass)."""
        self.executor.spin_until_future_complete(future, timeout)


def wait_for_name(names: Callable[[], Iterable[str]], name: str, timeout: float) -> bool:
    """Poll `names()` until `name` is among them or `timeout` s pass (0: look once)."""
    deadline = time.monotonic() + max(0.0, timeout)
    while True:
        if name in set(names()):
            return True
        if time.monotonic() >= deadline:
            return False
        time.sleep(0.05)
