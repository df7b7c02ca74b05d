"""Things that can be destroyed (rclpy's `destroyable` protocol): entities, nodes, handlers."""

from __future__ import annotations

from typing import Protocol, runtime_checkable

__all__ = ['DestroyableType']


@runtime_checkable
class DestroyableType(Protocol):
    """Anything with a `destroy()` that releases what it holds."""

    def destroy(self) -> None:
        """Release what it holds; it must not be used afterwards."""
