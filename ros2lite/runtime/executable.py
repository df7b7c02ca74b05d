"""What subscriptions, services, clients, timers and guard conditions share: they belong to a
node and a callback group, and when work arrives (on any thread) they tell their node's
:class:`~ros2lite.runtime.scheduling.NodeWork`, which queues them on the node's executor at
most once until it has run them.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, Protocol, TypeVar

from ros2lite.callback_groups import CallbackGroup, MutuallyExclusiveCallbackGroup
from ros2lite.runtime.parking import Parking
from ros2lite.runtime.scheduling import NodeWork, Scheduled
from ros2lite.task import TaskRunner

if TYPE_CHECKING:
    from ros2lite.context import Context
    from ros2lite.logging import RcutilsLogger
    from ros2lite.task import Task

__all__ = [
    'RUNNING',
    'Destroyable',
    'EntityExecutor',
    'EntityNode',
    'Executable',
    'GuardCondition',
    'NodeExecutor',
    'current_execution',
]


class _Running(threading.local):
    """What this thread is executing (class defaults: nothing, read without getattr)."""

    executor: EntityExecutor | None = None
    entity: Executable | None = None


# which executor and entity the current thread runs a callback for (set by the executor that
# runs it, read here): coroutine callbacks continue on it, blocking calls check it for deadlocks
RUNNING = _Running()
# the node a NodeExecutor takes (contravariant: it only goes in)
_NodeT = TypeVar('_NodeT', contravariant=True)


class Destroyable(Protocol):
    """Anything a node tears down when it is destroyed."""

    def destroy(self) -> None:
        """Release what it holds (entities leave the graph)."""
        ...


class EntityExecutor(Protocol):
    """The executor as the entities it runs see it (:class:`ros2lite.executors.Executor`):
    named here so that entities sit below the executor that imports them."""

    def wake(self) -> None:
        """Any thread: make a waiting spin look again."""
        ...

    def run_callback(
        self,
        callback: Callable[..., object],
        *args: object,
        then: Callable[[object], None] | None = None,
    ) -> Task | None:
        """Call a user callback on the executor's terms (a coroutine goes on as a Task)."""
        ...


class NodeExecutor(EntityExecutor, TaskRunner, Protocol[_NodeT]):
    """The executor a node was added to (:class:`ros2lite.executors.Executor` is one), as the
    node sees it: named below both, as executors import nodes to run them. The node's type is
    a parameter (node.py says `NodeExecutor[Node]`), so this floor names nothing above it."""

    def add_node(self, node: _NodeT) -> bool:
        """Take over `node`."""
        ...

    def remove_node(self, node: _NodeT) -> None:
        """Stop running `node`'s work."""
        ...

    @property
    def parks(self) -> bool:
        """Whether an idle spin waits in a kept channel (parking) instead of its queue."""
        ...

    def keeps_here(self) -> bool:
        """Whether the calling thread spins this executor, which would park."""
        ...


class EntityNode(Protocol):
    """The node as the entities it owns see it (:class:`ros2lite.node.Node` is one): what
    subscriptions, services, clients, timers and endpoints ask of their node, named here so
    that they sit below the node that makes them."""

    @property
    def context(self) -> Context:
        """The context whose session the node's entities use."""
        ...

    @property
    def node_id(self) -> int:
        """The node's id within its context (part of every token of its entities)."""
        ...

    @property
    def default_callback_group(self) -> CallbackGroup:
        """The group of entities that were given none."""
        ...

    @property
    def work(self) -> NodeWork[Any]:
        """Who runs the node's work: its executor and what waits for one."""
        ...

    @property
    def parking(self) -> Parking:
        """Where the node's executor waits when idle: its kept channels."""
        ...

    def get_name(self) -> str:
        """The node's name."""
        ...

    def get_namespace(self) -> str:
        """The node's namespace."""
        ...

    def resolve_topic_name(self, topic: str, *, only_expand: bool = False) -> str:
        """A topic name as this node resolves it (expansion, remapping)."""
        ...

    def resolve_service_name(self, service: str, *, only_expand: bool = False) -> str:
        """A service name as this node resolves it."""
        ...

    def get_logger(self) -> RcutilsLogger:
        """The node's logger."""
        ...

    def remove_waitable(self, waitable: Executable) -> None:
        """Stop running `waitable` with this node."""
        ...


def current_execution() -> tuple[EntityExecutor | None, Executable | None]:
    """(executor, entity) whose callback this thread is running, or (None, None)."""
    return RUNNING.executor, RUNNING.entity


class Executable(Scheduled):
    """Base of everything an executor runs for a node."""

    # completing a client's future runs no user callback of its own, so it need not wait for
    # its group: a coroutine holding the group while it awaits that very future would
    # otherwise never resume
    needs_group = True
    is_timer = False

    def __init__(self, node: EntityNode | None, callback_group: CallbackGroup | None) -> None:

        self._node = node
        self.callback_group = callback_group or (
            node.default_callback_group if node is not None else MutuallyExclusiveCallbackGroup()
        )
        self.callback_group.add_entity(self)

    def settle_owner(self, node: EntityNode) -> EntityNode | None:
        """Make `node` its owner unless it has one; the owner it had (None: joined now). A
        waitable joins the node that adds it; a node adopting an entity checks the owner."""
        owner = self._node
        if owner is None:
            self._node = node
        return owner

    def _notify(self) -> None:
        """Any thread: work arrived; the node's NodeWork queues this entity (once)."""
        # only entities of a node queue work (a nodeless timer is never notified)
        self._node.work.notify(self)  # type: ignore[union-attr]

    def runs_on(self, executor: object) -> bool:
        """Whether its node is attached to `executor` now."""
        node = self._node
        return node is not None and node.work.executor is executor

    def _call(
        self,
        callback: Callable[..., object],
        *args: object,
        then: Callable[[Any], None] | None = None,  # gets what the user's callback returned
    ) -> Task | None:
        """Run a user callback on the executor's terms (a coroutine becomes a Task). That is
        the executor running this entity now: a multi-threaded one may run it after the node
        has moved on (spin_once's helper removes the node once the work is handed over)."""
        executor = RUNNING.executor
        if executor is None and self._node is not None:
            executor = self._node.work.executor
        if executor is not None:
            return executor.run_callback(callback, *args, then=then)
        result = callback(*args)
        if then is not None:
            then(result)
        return None

    def run_pending(self, batch: bool, stop: Callable[[], bool] | None) -> Task | None:
        """Run pending work; return a Task if a coroutine callback is still running (it
        keeps the callback group until it finishes)."""
        raise NotImplementedError


class GuardCondition(Executable):
    """`trigger()` from any thread makes the executor call `callback()` on its thread."""

    def __init__(
        self,
        node: EntityNode | None,
        callback: Callable[[], object] | None,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        super().__init__(node, callback_group)
        self.callback = callback
        self._triggered = False

    def trigger(self) -> None:
        """Any thread: have the executor run the callback (once per trigger burst)."""
        self._triggered = True
        self._notify()

    def has_work(self) -> bool:
        return self._triggered

    def run_pending(self, batch: bool, stop: Callable[[], bool] | None) -> Task | None:
        self._triggered = False
        return self._call(self.callback) if self.callback is not None else None

    def destroy(self) -> None:
        """Never run the callback again."""
        self.callback = None
