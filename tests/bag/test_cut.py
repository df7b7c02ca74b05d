"""`bag cut`/`bag filter` as a library: the kept chunks copied as bytes, the edges re-encoded,
the result read back by ros2lite, `rosbags` and `mcap` (CRCs checked) as the same messages."""

from __future__ import annotations

import glob
from pathlib import Path

import pytest

from ros2lite.bag import BagError, Reader, Writer
from ros2lite.bag.cut import cut, parse_time
from ros2lite.msgs.sensor_msgs.msg import Imu
from ros2lite.msgs.std_msgs.msg import String

DATA = Path(__file__).parent / "data"
T0 = 1_700_000_000_000_000_000
MS = 1_000_000


def make_bag(path: Path, n: int = 2000, **options: object) -> None:
    """/chatter every 10 ms, /imu every 20 ms, in small chunks (many of them per second)."""
    with Writer(path, chunk_size=4096, **options) as w:  # type: ignore[arg-type]
        for i in range(n):
            w.write("/chatter", String(data=f"hello {i}"), T0 + i * 10 * MS)
            if i % 2 == 0:
                w.write("/imu", Imu(), T0 + i * 10 * MS + 1)


def messages(bag: Path, **kwargs: object) -> list[tuple[str, bytes, int, int]]:
    with Reader(bag) as r:
        return list(r.raw_messages(**kwargs))  # type: ignore[arg-type]


def independent_reads(bag: Path) -> tuple[int, int]:
    """(messages rosbags decodes, messages mcap reads with CRCs checked)."""
    from mcap.reader import make_reader
    from rosbags.highlevel import AnyReader

    with AnyReader([bag]) as ar:
        decoded = 0
        for conn, _, raw in ar.messages():
            ar.deserialize(raw, conn.msgtype)
            decoded += 1
    read = 0
    for f in sorted(glob.glob(str(bag / "*.mcap"))):
        with open(f, "rb") as stream:
            read += sum(1 for _ in make_reader(stream, validate_crcs=True).iter_messages())
    return decoded, read


@pytest.mark.parametrize("compression", ["none", "zstd"])
def test_cut_copies_inner_chunks_and_keeps_exactly_the_range(
    tmp_path: Path, compression: str
) -> None:
    make_bag(tmp_path / "src", compression=compression)
    start, end = T0 + 5_000 * MS, T0 + 10_000 * MS
    result = cut(tmp_path / "src", tmp_path / "out", start=start, end=end)
    assert result.spliced and result.chunks_copied > 10
    assert result.chunks_rewritten <= 2  # the two edges only
    want = messages(tmp_path / "src", start=start, stop=end + 1)
    got = messages(tmp_path / "out")
    assert got == want and len(want) == 751
    m = result.metadata
    assert m.message_count == 751 and m.starting_time == start and m.duration == end - start
    counts = {t.topic_metadata.name: t.message_count for t in m.topics_with_message_count}
    assert counts == {"/chatter": 501, "/imu": 250}
    with Reader(tmp_path / "out") as r:  # metadata.yaml as written
        assert r.metadata.message_count == 751
        assert r.topic("/imu").type_description_hash.startswith("RIHS01_")  # type: ignore[union-attr]
    assert independent_reads(tmp_path / "out") == (751, 751)


def test_filter_leaves_no_record_of_a_dropped_topic(tmp_path: Path) -> None:
    from mcap.records import Channel
    from mcap.stream_reader import StreamReader

    # /late appears only at the end: the chunks before hold /chatter alone but the first
    # one registers /late's channel, so it is re-encoded and the others copied
    with Writer(tmp_path / "src", chunk_size=4096) as w:
        w.create_topic("/late", "std_msgs/msg/String")
        for i in range(1000):
            w.write("/chatter", String(data=f"m{i}"), T0 + i * MS)
        w.write("/late", String(data="late"), T0 + 1000 * MS)
    result = cut(tmp_path / "src", tmp_path / "out", topics=["chatter"])
    assert result.chunks_copied > 5 and result.chunks_rewritten >= 1
    assert [t.topic_metadata.name for t in result.metadata.topics_with_message_count] == [
        "/chatter"
    ]
    with open(glob.glob(str(tmp_path / "out" / "*.mcap"))[0], "rb") as f:
        topics = {
            r.topic for r in StreamReader(f, validate_crcs=True).records if isinstance(r, Channel)
        }
    assert topics == {"/chatter"}
    assert messages(tmp_path / "out") == messages(tmp_path / "src", topics=["/chatter"])
    assert independent_reads(tmp_path / "out") == (1000, 1000)
    result = cut(tmp_path / "src", tmp_path / "out2", exclude=["/chatter"])
    assert result.metadata.message_count == 1


def test_a_split_bag_is_cut_file_by_file(tmp_path: Path) -> None:
    make_bag(tmp_path / "src", n=600, max_bag_size=12_000)
    with Reader(tmp_path / "src") as r:
        assert len(r.files) >= 3
    start, end = T0 + 1_000 * MS, T0 + 5_000 * MS
    result = cut(tmp_path / "src", tmp_path / "out", start=start, end=end)
    assert len(result.metadata.files) >= 2
    assert messages(tmp_path / "out") == messages(tmp_path / "src", start=start, stop=end + 1)
    assert independent_reads(tmp_path / "out") == (result.metadata.message_count,) * 2


def test_inputs_without_a_summary_are_rewritten(tmp_path: Path) -> None:
    result = cut(DATA / "sqlite3" / "talker", tmp_path / "out", topics=["/topic"])
    assert not result.spliced
    assert result.metadata.message_count == len(
        messages(DATA / "sqlite3" / "talker", topics=["/topic"])
    )


def test_errors(tmp_path: Path) -> None:
    make_bag(tmp_path / "src", n=10)
    with pytest.raises(BagError, match="no topic /nope"):
        cut(tmp_path / "src", tmp_path / "out", topics=["/nope"])
    with pytest.raises(BagError, match="before its start"):
        cut(tmp_path / "src", tmp_path / "out", start=T0 + 5, end=T0)
    (tmp_path / "there").mkdir()
    with pytest.raises(BagError, match="already exists"):
        cut(tmp_path / "src", tmp_path / "there")
    assert not (tmp_path / "out").exists()


def test_parse_time() -> None:
    start = T0
    assert parse_time("90", start) == T0 + 90 * 10**9
    assert parse_time("12.5", start) == T0 + 12_500 * MS
    assert parse_time("1:30", start) == T0 + 90 * 10**9
    assert parse_time("1:02:03.5", start) == T0 + 3723_500 * MS
    assert parse_time("1700000100", start) == T0 + 100 * 10**9
    assert parse_time("1700000100000000001", start) == T0 + 100 * 10**9 + 1
    # as `bag echo` prints a stamp: every nanosecond kept (float lost the last digits)
    assert parse_time("1700000100.123456789", start) == T0 + 100 * 10**9 + 123_456_789
    assert parse_time("0:01.000000001", start) == T0 + 10**9 + 1
    assert parse_time("2023-11-14T22:13:20", start) == T0
    assert parse_time("2023-11-14T23:13:20.25+01:00", start) == T0 + 250 * MS
    for bad in ("xx", "-3", "1:75", "nan", "Infinity", "1e999999999"):
        with pytest.raises(BagError):
            parse_time(bad, start)


def test_a_lying_chunk_index_is_not_copied_on_its_word(tmp_path: Path) -> None:
    """Chunk indexes whose lengths do not match their chunks: those chunks are read (CRC
    checked) and re-encoded instead of copied, and the cut still holds the right messages."""
    import struct

    from mcap.reader import make_reader

    make_bag(tmp_path / "src", n=400)
    [f] = list((tmp_path / "src").glob("*.mcap"))
    with open(f, "rb") as stream:
        indexes = make_reader(stream).get_summary().chunk_indexes  # type: ignore[union-attr]
    data = bytearray(f.read_bytes())
    lied = 0
    for index in indexes[2:6]:
        # a ChunkIndex record: its start time, end time, offset, then the chunk's length
        head = struct.pack("<QQQQ", index.message_start_time, index.message_end_time,
                           index.chunk_start_offset, index.chunk_length)  # fmt: skip
        at = data.rfind(head)
        assert at > 0
        struct.pack_into("<Q", data, at + 24, index.chunk_length + 7)
        lied += 1
    f.write_bytes(bytes(data))
    result = cut(tmp_path / "src", tmp_path / "out")
    assert result.chunks_rewritten == lied and result.chunks_copied == len(indexes) - lied
    assert messages(tmp_path / "out") == messages(tmp_path / "src")
