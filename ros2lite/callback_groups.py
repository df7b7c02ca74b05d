"""Callback groups, as rclpy has them: which callbacks a multi-threaded executor may run at once.

A node's entities share its default `MutuallyExclusiveCallbackGroup` unless given another; a
`ReentrantCallbackGroup` lets its callbacks (even two of the same entity) run in parallel.
"""

from __future__ import annotations

import threading

__all__ = ['CallbackGroup', 'MutuallyExclusiveCallbackGroup', 'ReentrantCallbackGroup']


class CallbackGroup:
    """Decides whether an entity's callback may start now; told when it ends.

    Its entities (:class:`ros2lite.runtime.executable.Executable`) are only held and compared
    here, so a group takes any object, and sits below the entities that name it."""

    def __init__(self) -> None:
        self.entities: list[object] = []

    def add_entity(self, entity: object) -> None:
        """Make `entity`'s callbacks part of this group."""
        self.entities.append(entity)

    def has_entity(self, entity: object) -> bool:
        """Whether `entity` belongs to this group."""
        return entity in self.entities

    def can_execute(self, entity: object) -> bool:
        """Whether `entity`'s callback could start now (without claiming the group)."""
        raise NotImplementedError

    def beginning_execution(self, entity: object) -> bool:
        """Claim the group for `entity`'s callback; False if it must wait."""
        raise NotImplementedError

    def ending_execution(self, entity: object) -> None:
        """`entity`'s callback is over: the group is free again for it."""
        raise NotImplementedError


class ReentrantCallbackGroup(CallbackGroup):
    """Any number of its callbacks may run at the same time."""

    def can_execute(self, entity: object) -> bool:
        """Always: nothing in this group waits for anything else in it."""
        return True

    def beginning_execution(self, entity: object) -> bool:
        """Always succeeds."""
        return True

    def ending_execution(self, entity: object) -> None:
        """Nothing to release."""


class MutuallyExclusiveCallbackGroup(CallbackGroup):
    """One of its callbacks at a time (a coroutine callback holds it until it finishes)."""

    def __init__(self) -> None:
        super().__init__()
        self._lock = threading.Lock()
        self._active: object | None = None

    def can_execute(self, entity: object) -> bool:
        """Whether no callback of the group runs now."""
        return self._active is None

    def beginning_execution(self, entity: object) -> bool:
        """Claim the group unless one of its callbacks runs."""
        with self._lock:
            if self._active is None:
                self._active = entity
                return True
            return False

    def ending_execution(self, entity: object) -> None:
        """Release the group if `entity` holds it."""
        with self._lock:
            if self._active is entity:
                self._active = None
