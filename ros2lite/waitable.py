"""Waitables, as rclpy names them: something of a node that the executor runs, beyond the
built-in entities (action servers and clients are waitables).

rclpy's waitables put rcl handles into wait sets; ros2lite has no wait sets, so a waitable
of one's own tells the executor it has work by calling :meth:`Waitable.notify_ready` (from
any thread). The executor then calls `take_data()` and `execute(data)` (a coroutine is
fine) in the waitable's callback group.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Generic, TypeVar, cast

from ros2lite.runtime.executable import Executable

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.task import Task

__all__ = ['NumberOfEntities', 'Waitable']

# what take_data() hands to execute()
T = TypeVar('T')


@dataclass
class NumberOfEntities:
    """How many entities of each kind a waitable holds (rclpy's bookkeeping record)."""

    num_subscriptions: int = 0
    num_guard_conditions: int = 0
    num_timers: int = 0
    num_clients: int = 0
    num_services: int = 0
    num_events: int = 0

    def __add__(self, other: NumberOfEntities) -> NumberOfEntities:
        return NumberOfEntities(
            self.num_subscriptions + other.num_subscriptions,
            self.num_guard_conditions + other.num_guard_conditions,
            self.num_timers + other.num_timers,
            self.num_clients + other.num_clients,
            self.num_services + other.num_services,
            self.num_events + other.num_events,
        )


class Waitable(Executable, Generic[T]):
    """Base of user waitables: override `take_data` and `execute`; call `notify_ready()`."""

    def __init__(self, callback_group: CallbackGroup | None = None) -> None:
        # the node is set when the waitable is added to one (Node.add_waitable)
        super().__init__(None, callback_group)
        self._ready = False

    def notify_ready(self) -> None:
        """Any thread: there is work; the executor will call take_data() and execute()."""
        self._ready = True
        if self._node is not None:
            self._notify()

    def has_work(self) -> bool:
        return self._ready

    def run_pending(self, batch: bool, stop: Callable[[], bool] | None) -> Task | None:
        self._ready = False
        return self._call(self.execute, self.take_data())

    # -- rclpy's interface -------------------------------------------------------------------
    def is_ready(self, wait_set: object) -> bool:
        """Whether there is work (here: whether notify_ready() was called since the last
        execution)."""
        return self._ready

    def take_data(self) -> T:
        """Take what the work needs; given to execute() (None unless overridden)."""
        return cast(T, None)

    async def execute(self, taken_data: T) -> None:
        """Do the work."""

    def get_num_entities(self) -> NumberOfEntities:
        """What rclpy would count in its wait set for this waitable (none by default)."""
        return NumberOfEntities()

    def add_to_wait_set(self, wait_set: object) -> None:
        """rclpy's wait-set hook; ros2lite has no wait sets, so nothing to add."""

    def destroy(self) -> None:
        """Remove it from its node."""
        if self._node is not None:
            self._node.remove_waitable(self)
