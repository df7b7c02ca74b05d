"""One Duration for the whole package: ROS time arithmetic and QoS policies alike.

Shaped like rclpy's (`Duration(seconds=1.5)`, `.nanoseconds`, `to_msg()`), plus the
`rmw_time_t` view (`sec`, `nsec`) that QoS tokens and `topic info -v` print. A module of its
own, with no imports from the rest of the package, so both the transport layer and the
client library can use it.
"""

from __future__ import annotations

from functools import total_ordering
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ros2lite.msgs.builtin_interfaces import msg as _builtin_msg

_NS = 1_000_000_000


@total_ordering
class Duration:
    """A signed span of time, held as whole nanoseconds."""

    __slots__ = ('_ns',)

    def __init__(self, *, seconds: float = 0, nanoseconds: int = 0) -> None:
        self._ns = int(nanoseconds) + (round(seconds * _NS) if seconds else 0)

    @classmethod
    def from_seconds(cls, seconds: float) -> Duration:
        """A duration of `seconds` (rounded to ns)."""
        return cls(seconds=seconds)

    @classmethod
    def from_nanoseconds(cls, nanoseconds: int) -> Duration:
        """A duration of `nanoseconds`."""
        return cls(nanoseconds=nanoseconds)

    @classmethod
    def from_msg(cls, msg: _builtin_msg.Duration | _builtin_msg.Time) -> Duration:
        """From a `builtin_interfaces/msg/Duration` (or anything with sec/nanosec)."""
        return cls(nanoseconds=msg.sec * _NS + msg.nanosec)

    @property
    def nanoseconds(self) -> int:
        """The length in nanoseconds."""
        return self._ns

    @property
    def sec(self) -> int:
        """Whole seconds of the `rmw_time_t` form (nanoseconds floor-divided)."""
        return self._ns // _NS

    @property
    def nsec(self) -> int:
        """The nanoseconds left over after `sec`, always in [0, 1e9)."""
        return self._ns % _NS

    @property
    def is_unspecified(self) -> bool:
        """Whether it is zero (QoS: the middleware's default)."""
        return self._ns == 0

    @property
    def is_infinite(self) -> bool:
        """Whether it is QoS's "infinite"."""
        return self._ns == _INFINITE_NS

    def to_seconds(self) -> float:
        """The length in seconds."""
        return self._ns / _NS

    def to_msg(self) -> _builtin_msg.Duration:
        """As a builtin_interfaces/Duration."""
        from ros2lite.interfaces import get_interface

        duration_type: type[_builtin_msg.Duration] = get_interface(
            'builtin_interfaces/msg/Duration'
        )
        return duration_type(sec=self.sec, nanosec=self.nsec)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Duration) and self._ns == other._ns

    def __hash__(self) -> int:
        return hash(self._ns)

    def __lt__(self, other: Duration) -> bool:
        return self._ns < other._ns

    def __add__(self, other: Duration) -> Duration:
        if not isinstance(other, Duration):
            return NotImplemented
        return Duration(nanoseconds=self._ns + other._ns)

    def __sub__(self, other: Duration) -> Duration:
        if not isinstance(other, Duration):
            return NotImplemented
        return Duration(nanoseconds=self._ns - other._ns)

    def __neg__(self) -> Duration:
        return Duration(nanoseconds=-self._ns)

    def __repr__(self) -> str:
        return f'Duration(nanoseconds={self._ns})'

    def __str__(self) -> str:
        # the wording of `topic info -v`'s QoS block
        return 'Infinite' if self.is_infinite else f'{self._ns} nanoseconds'


# rmw's "infinite" QoS duration: {INT64_MAX / 1e9 s, INT64_MAX % 1e9 ns}
_INFINITE_NS = 9223372036 * _NS + 854775807
