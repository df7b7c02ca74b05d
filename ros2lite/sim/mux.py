"""A robot's twist multiplexer, as twist_mux decides (TIAGo's launch runs one): of the
velocity inputs, the highest-priority one heard within its timeout drives.

Apart from `body` because it is a rule of its own, with no ROS in it: it is read, and
tested, without a simulator running.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

__all__ = ['TwistMux']


class TwistMux:
    """Inputs as (topic, priority, timeout s); a timeout <= 0 keeps an input live for ever
    once heard. Not thread-safe: the body calls it under the simulator's lock."""

    def __init__(self, inputs: Iterable[tuple[str, int, float]]) -> None:
        self._inputs = {name: (priority, timeout) for name, priority, timeout in inputs}
        self._heard = dict.fromkeys(self._inputs, -math.inf)

    @property
    def names(self) -> list[str]:
        """The input topics, in the order given."""
        return list(self._inputs)

    def admits(self, name: str, now: float) -> bool:
        """A command on input `name` at sim time `now` (remembered as heard): whether it
        drives, that is no other input of higher priority is live."""
        priority, _ = self._inputs[name]
        self._heard[name] = now
        for other, (p, t) in self._inputs.items():
            heard = self._heard[other]
            live = t <= 0 or now - heard <= t
            if other != name and p > priority and live and heard > -math.inf:
                return False
        return True
