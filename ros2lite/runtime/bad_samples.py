"""Samples that cannot be decoded: dropped, counted, and reported without flooding.

Anyone on the network can publish on a topic, so a payload that is not the topic's type (empty,
truncated, garbage, a length field of four billion) is an everyday event, not a reason for a
subscriber to die. Every place that decodes samples from outside (typed subscriptions, hence
action feedback and status and a node's ``/clock``; ``topic echo``) hands such a sample to a
:class:`BadSamples` of its topic, which

* counts it, in total and per publisher (by the GID from the rmw_zenoh attachment);
* warns once for each publisher, naming the topic, the publisher and what was wrong;
* rate-limits those warnings (a peer can invent a new GID for every sample): at most one per
  `interval` seconds, the ones held back summed up in the next;
* keeps at most `max_publishers` publishers in its table (the oldest is forgotten first), so
  its memory is bounded whatever arrives;
* counts samples without an attachment (no ROS message: a peer's, perhaps a flood of them)
  apart, with one warning for them all.
"""

from __future__ import annotations

import threading
import time
from collections import OrderedDict
from collections.abc import Callable

from ros2lite.topic_endpoint_info import format_gid
from ros2lite.transport.attachment import unpack_attachment

__all__ = ['BadSamples', 'describe_publisher']

MAX_PUBLISHERS = 256
WARN_INTERVAL = 1.0


def describe_publisher(gid: bytes) -> str:
    """A publisher as a warning names it: its GID in hex (what `topic info -v` shows)."""
    if not gid:
        return 'an unknown publisher (no attachment)'
    return 'publisher ' + format_gid(gid)


def gid_of(attachment: bytes | None) -> bytes:
    """The publisher GID of an rmw_zenoh attachment (b'' when there is none or it is bad)."""
    if not attachment:
        return b''
    fields = unpack_attachment(attachment)
    return fields[2] if fields is not None else b''


class BadSamples:
    """The undecodable samples of one topic (see the module doc).

    `warn(text)` gets the warnings; `clock()` is a monotonic clock in seconds (tests pass
    their own)."""

    def __init__(
        self,
        topic: str,
        type_name: str,
        warn: Callable[[str], object],
        *,
        interval: float = WARN_INTERVAL,
        max_publishers: int = MAX_PUBLISHERS,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.topic = topic
        self.type_name = type_name
        self.total = 0
        self._warn = warn
        self._interval = interval
        self._max = max(1, max_publishers)
        self._clock = clock
        self._lock = threading.Lock()
        self._counts: OrderedDict[bytes, int] = OrderedDict()
        self._next_warning = float('-inf')
        self._held = 0  # new publishers not warned about because of the rate limit
        # samples without an attachment (in `total` too), and whether they were warned about
        self.unattached = 0
        self._warned_unattached = False

    @property
    def publishers(self) -> int:
        """Publishers in the table now (at most `max_publishers`)."""
        return len(self._counts)

    def count(self, gid: bytes) -> int:
        """Bad samples seen from one publisher (0 once it has been forgotten)."""
        return self._counts.get(gid, 0)

    def add(self, gid: bytes, error: BaseException | str, size: int) -> None:
        """One dropped sample of `size` bytes from the publisher `gid`, and why."""
        with self._lock:
            self.total += 1
            seen = self._counts.get(gid)
            if seen is not None:
                self._counts[gid] = seen + 1
                self._counts.move_to_end(gid)
                return
            self._counts[gid] = 1
            while len(self._counts) > self._max:
                self._counts.popitem(last=False)
            now = self._clock()
            if now < self._next_warning:
                self._held += 1
                return
            self._next_warning = now + self._interval
            held, self._held = self._held, 0
        text = (
            f"dropped a sample on '{self.topic}' from {describe_publisher(gid)}: "
            f'not a valid {self.type_name} ({size} bytes: {error}); further bad samples from '
            'this publisher are dropped without a word'
        )
        if held:
            text += f'; {held} other publisher(s) sent bad samples since the last warning'

        self._warn(text)

    def add_unattached(self, count: int) -> None:
        """`count` dropped samples without an attachment (not ROS messages: rmw_zenoh drops
        them too, and a flood of them is a peer's doing): counted, warned about once."""
        with self._lock:
            self.total += count
            self.unattached += count
            if self._warned_unattached:
                return
            self._warned_unattached = True
        self._warn(
            f"dropped a sample without an attachment on '{self.topic}' (not a ROS message); "
            'further ones are counted without a word'
        )
