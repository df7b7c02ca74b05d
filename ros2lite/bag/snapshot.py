"""Snapshot recording (rosbag2's snapshot mode): the recorder's messages go into a ring buffer
in memory holding the last DURATION (and at most `max_bytes`), and only a trigger — the
`~/snapshot` service (rosbag2_interfaces/srv/Snapshot) or SIGUSR1 — writes it out.

`SnapshotWriter` is the bag `Writer` the recorder writes into: its `write_raw` only buffers.
Each snapshot writes what the buffer holds from the trigger's time back DURATION (nothing
older, nothing after the trigger) into the bag, one file per snapshot (`<bag>_0.mcap`,
`<bag>_1.mcap`, ...), and empties the buffer, so two snapshots never hold the same message.
"""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Callable
from typing import TYPE_CHECKING

from ros2lite.bag.errors import BagError
from ros2lite.bag.writer import Writer

if TYPE_CHECKING:
    import os

    from ros2lite.bag.recorder import Recorder

__all__ = ["SNAPSHOT_SERVICE", "SnapshotWriter", "take_snapshot"]

SNAPSHOT_SERVICE = "rosbag2_interfaces/srv/Snapshot"
# what one buffered message costs beyond its bytes (the tuple and its ints), for the bound
_ENTRY_OVERHEAD = 120


class SnapshotWriter(Writer):
    """A bag written only on `snapshot()`: messages are kept in memory meanwhile, the newest
    `duration` seconds of them (0: no time bound) and never more than `max_bytes`."""

    def __init__(
        self,
        uri: str | os.PathLike[str],
        *,
        duration: float,
        max_bytes: int,
        **options: object,
    ) -> None:
        if duration < 0:
            raise BagError("The snapshot duration must not be negative")
        if duration == 0 and max_bytes <= 0:
            raise BagError("A snapshot needs a duration or a --max-cache-size above 0")
        super().__init__(uri, **options)  # type: ignore[arg-type]
        self.duration_ns = int(duration * 1e9)
        self.max_bytes = max_bytes
        self._ring: deque[tuple[int, bytes, int, int]] = deque()
        self._ring_bytes = 0
        self._ring_lock = threading.Lock()
        self.snapshots = 0
        self.dropped = 0  # messages pushed out by the size bound before their time was up

    @property
    def buffered(self) -> int:
        """Messages in the buffer now."""
        return len(self._ring)

    @property
    def buffered_bytes(self) -> int:
        """What the buffer holds, as counted against `max_bytes`."""
        return self._ring_bytes

    def write_raw(self, tid: int, data: bytes, log_time: int, publish_time: int) -> None:
        """Buffer one message; what is older than the duration (counted from this message)
        or past the size bound goes."""
        cost = len(data) + _ENTRY_OVERHEAD
        with self._ring_lock:
            ring = self._ring
            ring.append((tid, data, log_time, publish_time))
            self._ring_bytes += cost
            if self.duration_ns:
                horizon = log_time - self.duration_ns
                while ring and ring[0][2] < horizon:
                    self._ring_bytes -= len(ring.popleft()[1]) + _ENTRY_OVERHEAD
            if self.max_bytes > 0:
                while self._ring_bytes > self.max_bytes and len(ring) > 1:
                    self._ring_bytes -= len(ring.popleft()[1]) + _ENTRY_OVERHEAD
                    self.dropped += 1

    def flush(self) -> None:
        """Nothing to put on disk between snapshots."""

    def snapshot(self, now: int | None = None) -> int:
        """Write the buffered messages logged from `now` - duration to `now` (ns; default the
        wall clock) as a file of the bag; the number written. The buffer is emptied."""
        if now is None:
            now = time.time_ns()
        horizon = now - self.duration_ns if self.duration_ns else None
        with self._ring_lock:
            taken = [m for m in self._ring if m[2] <= now and (horizon is None or m[2] >= horizon)]
            keep = deque(m for m in self._ring if m[2] > now)  # arrived after the trigger
            self._ring = keep
            self._ring_bytes = sum(len(m[1]) + _ENTRY_OVERHEAD for m in keep)
        taken.sort(key=lambda m: m[2])
        if not taken:
            return 0
        if self.message_count:
            self.split()  # one file per snapshot
        write = super().write_raw
        for tid, data, log_time, publish_time in taken:
            write(tid, data, log_time, publish_time)
        super().flush()
        self.snapshots += 1
        return len(taken)


def take_snapshot(
    recorder: Recorder, writer: SnapshotWriter, now: int, *, drain_timeout: float = 2.0
) -> int:
    """A snapshot at `now` of what `recorder` received up to it: the recorder's queue (what
    reached the process but not the buffer yet) is let drain first, for at most
    `drain_timeout` seconds."""
    deadline = time.monotonic() + drain_timeout
    while recorder.queued() and time.monotonic() < deadline:
        time.sleep(0.001)
    return writer.snapshot(now)


def snapshot_handler(
    recorder: Recorder, writer: SnapshotWriter, now: Callable[[], int], log: Callable[[str], object]
) -> Callable[[], bool]:
    """What a trigger runs: a snapshot, said in the log; False when it could not be written."""

    def trigger() -> bool:
        try:
            n = take_snapshot(recorder, writer, now())
        except (BagError, OSError) as e:
            log(f"Snapshot failed: {e}")
            return False
        log(f"Snapshot: wrote {n} messages (the last {writer.duration_ns / 1e9:g} s)")
        return True

    return trigger
