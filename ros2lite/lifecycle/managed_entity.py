"""Entities that follow their node's lifecycle: enabled while it is active (rclpy's shape)."""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any, TypeVar, overload

from ros2lite.lifecycle.state_machine import LifecycleState, TransitionCallbackReturn

__all__ = ['ManagedEntity', 'SimpleManagedEntity']

F = TypeVar('F', bound=Callable[..., Any])


class ManagedEntity:
    """Something a lifecycle node switches on when it activates and off when it deactivates."""

    def on_activate(self, state: LifecycleState) -> TransitionCallbackReturn:
        """The node is activating."""
        raise NotImplementedError

    def on_deactivate(self, state: LifecycleState) -> TransitionCallbackReturn:
        """The node is deactivating."""
        raise NotImplementedError


class SimpleManagedEntity(ManagedEntity):
    """A managed entity that is simply enabled or not; methods decorated with
    :meth:`when_enabled` do nothing while it is not."""

    def __init__(self) -> None:
        self._enabled = False

    @property
    def is_activated(self) -> bool:
        """Whether the owning node has activated this entity."""
        return self._enabled

    def on_activate(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Enable the entity."""
        self._enabled = True
        return TransitionCallbackReturn.SUCCESS

    def on_deactivate(self, state: LifecycleState) -> TransitionCallbackReturn:
        """Disable the entity."""
        self._enabled = False
        return TransitionCallbackReturn.SUCCESS

    @overload
    @staticmethod
    def when_enabled(wrapped: F, *, when_not_enabled: Callable[[], object] | None = None) -> F:
        """`@when_enabled` on a method."""

    @overload
    @staticmethod
    def when_enabled(
        wrapped: None = None, *, when_not_enabled: Callable[[], object] | None = None
    ) -> Callable[[F], F]:
        """`@when_enabled(when_not_enabled=…)` on a method."""

    @staticmethod
    def when_enabled(
        wrapped: F | None = None, *, when_not_enabled: Callable[[], object] | None = None
    ) -> F | Callable[[F], F]:
        """Decorate a method so it runs only while the entity is enabled; otherwise
        `when_not_enabled()` (if given) runs instead and the call returns None."""

        def decorator(method: F) -> F:
            @functools.wraps(method)
            def only_when_enabled(
                self: SimpleManagedEntity, *args: object, **kwargs: object
            ) -> object:
                if not self._enabled:
                    if when_not_enabled is not None:
                        when_not_enabled()
                    return None
                return method(self, *args, **kwargs)

            return only_when_enabled  # type: ignore[return-value]

        return decorator if wrapped is None else decorator(wrapped)
