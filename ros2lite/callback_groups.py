"""Callback groups, as rclpy has them: which callbacks a multi-threaded executor may run at once.

A node's entities share its default `MutuallyExclusiveCallbackGroup` unless given another; a
`ReentrantCallbackGroup` lets its callbacks (even two of the same entity) run in parallel.
"""

from __future__ import annotations

import threading
from typing import Any

__all__ = ['CallbackGroup', 'MutuallyExclusiveCallbackGroup', 'ReentrantCallbackGroup']


class CallbackGroup:
    """Decides whether an entity's callback may start now; told when it ends."""

    def __init__(self) -> None:
        self.entities: list[Any] = []

    def add_entity(self, entity: Any) -> None:
        self.entities.append(entity)

    def has_entity(self, entity: Any) -> bool:
        return entity in self.entities

    def can_execute(self, entity: Any) -> bool:
        raise NotImplementedError

    def beginning_execution(self, entity: Any) -> bool:
        """Claim the group for `entity`'s callback; False if it must wait."""
        raise NotImplementedError

    def ending_execution(self, entity: Any) -> None:
        raise NotImplementedError


class ReentrantCallbackGroup(CallbackGroup):
    """Any number of its callbacks may run at the same time."""

    def can_execute(self, entity: Any) -> bool:
        return True

    def beginning_execution(self, entity: Any) -> bool:
        return True

    def ending_execution(self, entity: Any) -> None:
        pass


class MutuallyExclusiveCallbackGroup(CallbackGroup):
    """One of its callbacks at a time (a coroutine callback holds it until it finishes)."""

    def __init__(self) -> None:
        super().__init__()
        self._lock = threading.Lock()
        self._active: Any = None

    def can_execute(self, entity: Any) -> bool:
        return self._active is None

    def beginning_execution(self, entity: Any) -> bool:
        with self._lock:
            if self._active is None:
                self._active = entity
                return True
            return False

    def ending_execution(self, entity: Any) -> None:
        with self._lock:
            if self._active is entity:
                self._active = None
