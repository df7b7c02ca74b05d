"""Rate: keep a loop running at a frequency (rclpy's `node.create_rate(hz)`).

`sleep()` blocks until the node's next tick of a timer of that period, so a loop that does
its work and then sleeps runs once per period whatever the work took. The ticks are timer
callbacks, so the node must be spun by another thread (as with rclpy).
"""

from __future__ import annotations

import threading
from typing import TYPE_CHECKING

from ros2lite.exceptions import ROSInterruptException

if TYPE_CHECKING:
    from ros2lite.clock import Clock
    from ros2lite.node_interface import NodeInterface

__all__ = ['Rate']


class Rate:
    """Sleeps until the next tick; ROSInterruptException once destroyed or shut down."""

    def __init__(self, node: NodeInterface, frequency: float, clock: Clock | None = None) -> None:
        if isinstance(frequency, bool) or not isinstance(frequency, (int, float)):
            raise TypeError(f'frequency must be a number, not {type(frequency).__name__}')
        if frequency <= 0:
            raise ValueError('frequency must be > 0')
        self._node = node
        self._context = node.context
        self._ticked = threading.Condition()
        self._ticks = 0
        self._destroyed = False
        self._timer = node.create_timer(1.0 / frequency, self._tick, clock=clock)
        self._context.on_shutdown(self.destroy)

    def _tick(self) -> None:
        with self._ticked:
            self._ticks += 1
            self._ticked.notify_all()

    def sleep(self) -> None:
        """Block until the next tick."""
        with self._ticked:
            if self._destroyed:
                raise ROSInterruptException('the rate was destroyed')
            seen = self._ticks
            while self._ticks == seen and not self._destroyed:
                self._ticked.wait()
            if self._destroyed:
                raise ROSInterruptException('the rate was destroyed while sleeping')

    def destroy(self) -> None:
        """Stop ticking; sleepers wake with ROSInterruptException."""
        with self._ticked:
            if self._destroyed:
                return
            self._destroyed = True
            self._ticked.notify_all()
        self._context.remove_on_shutdown(self.destroy)
        self._node.destroy_timer(self._timer)
