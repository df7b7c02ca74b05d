"""The snapshot ring buffer: it keeps the newest DURATION and at most its byte bound, each
snapshot writes exactly the window before its time into a file of its own, and what came after
the trigger waits for the next one."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite.bag import BagError, Reader
from ros2lite.bag.snapshot import SnapshotWriter
from ros2lite.interfaces import serialize
from ros2lite.msgs.std_msgs.msg import String

S = 1_000_000_000


def test_each_snapshot_holds_the_window_before_it(tmp_path: Path) -> None:
    w = SnapshotWriter(tmp_path / "bag", duration=2.0, max_bytes=10**9).open()
    tid = w.create_topic("/s", "std_msgs/msg/String")
    for i in range(100):  # 10 s at 10 Hz
        w.write_raw(tid, serialize(String(data=str(i))), i * S // 10, i * S // 10)
    assert w.buffered == 21  # 7.9 s .. 9.9 s: the rest was older than 2 s
    # a snapshot "at 9.5 s": the 2 s before it, and not what arrived after it
    assert w.snapshot(now=95 * S // 10) == 21 - 4
    assert w.buffered == 4
    for i in range(100, 150):
        w.write_raw(tid, serialize(String(data=str(i))), i * S // 10, i * S // 10)
    assert w.snapshot(now=15 * S) == 20  # 13 s .. 14.9 s
    assert w.snapshot(now=16 * S) == 0  # nothing new: no empty file
    w.close()
    with Reader(tmp_path / "bag") as r:
        assert [Path(f).name for f in r.metadata.relative_file_paths] == [
            "bag_0.mcap",
            "bag_1.mcap",
        ]
        first = [int(m.data) for _, m, _ in r.messages()]  # type: ignore[union-attr]
        assert r.metadata.files[0].message_count == 17
    assert first == [*range(79, 96), *range(130, 150)]


def test_the_byte_bound_pushes_out_the_oldest(tmp_path: Path) -> None:
    w = SnapshotWriter(tmp_path / "bag", duration=0, max_bytes=10_000).open()
    tid = w.create_topic("/s", "std_msgs/msg/String")
    data = serialize(String(data="x" * 1000))
    for i in range(100):
        w.write_raw(tid, data, i, i)
    assert w.buffered_bytes <= 10_000 and w.buffered == 8 and w.dropped == 92
    assert w.snapshot(now=1000) == 8
    w.close()
    with Reader(tmp_path / "bag") as r:
        assert [t for _, _, t in r.messages()] == list(range(92, 100))


def test_bad_bounds(tmp_path: Path) -> None:
    with pytest.raises(BagError, match="needs a duration"):
        SnapshotWriter(tmp_path / "a", duration=0, max_bytes=0)
    with pytest.raises(BagError, match="negative"):
        SnapshotWriter(tmp_path / "b", duration=-1, max_bytes=10)
