"""Numeric option types that refuse what no command can use: NaN, infinities, negatives
where a count or a duration is meant, and values too large for the clocks and buffers they
end up in. A bad number is a usage error (exit 2) naming the option, as ros2cli's argparse
types make it, never a Python error later on.
"""

from __future__ import annotations

import math
from typing import cast

import click

__all__ = ['MAX_COUNT', 'MAX_SECONDS', 'Count', 'Finite', 'Size', 'rate', 'seconds']

# the longest duration any option may ask for (about 3 years): far past any real wait, and
# well inside what time.sleep() and threading timeouts accept
MAX_SECONDS = 1e8
# the largest count (messages, bytes, milliseconds…): what a C ssize_t holds on any platform
MAX_COUNT = 2**31 - 1
MAX_RATE = 1e6  # Hz


class Finite(click.FloatRange):
    """A float within a range that is also a real number (no nan, inf)."""

    name = 'float'

    def convert(
        self, value: object, param: click.Parameter | None, ctx: click.Context | None
    ) -> float:
        if isinstance(value, str):
            try:
                number = float(value)
            except ValueError:
                self.fail(f'{value!r} is not a number.', param, ctx)
            if not math.isfinite(number):
                self.fail(f'{value!r} is not a finite number.', param, ctx)
        elif isinstance(value, float) and not math.isfinite(value):
            self.fail(f'{value!r} is not a finite number.', param, ctx)
        # click's range converts text and numbers alike (typed float there)
        return super().convert(cast(float, value), param, ctx)


class Count(click.IntRange):
    """An integer within a range (upper bound MAX_COUNT unless told)."""

    name = 'integer'

    def __init__(self, min: int | None = 0, max: int | None = MAX_COUNT, **kw: bool) -> None:
        super().__init__(min=min, max=max, **kw)


def seconds(min_open: bool = False, minimum: float = 0.0) -> Finite:
    """A duration in seconds: finite, not negative (positive with `min_open`), at most
    MAX_SECONDS."""
    return Finite(min=minimum, max=MAX_SECONDS, min_open=min_open)


def rate() -> Finite:
    """A rate in Hz: finite, at most MAX_RATE, and at least one period in MAX_SECONDS (a
    rate of 1e-300 Hz made a period no clock holds)."""
    return Finite(min=1 / MAX_SECONDS, max=MAX_RATE)


class Size(click.ParamType):
    """A picture size `WxH` in pixels, each side 64 to 8192."""

    name = 'size'

    def convert(
        self, value: object, param: click.Parameter | None, ctx: click.Context | None
    ) -> tuple[int, int]:
        if isinstance(value, tuple):
            return value
        parts = str(value).lower().split('x')
        try:
            width, height = (int(p) for p in parts)
        except ValueError:
            self.fail(f'{value!r} is not a size WIDTHxHEIGHT (as 800x480).', param, ctx)
        if not (64 <= width <= 8192 and 64 <= height <= 8192):
            self.fail(f'{value!r}: each side must be 64 to 8192 pixels.', param, ctx)
        return (width, height)
