"""Crafted bags (written with the `mcap` package, then damaged): a corrupt chunk is reported
with file and offset and skipped, a truncated bag says what it promised and what is readable,
and playback refuses log times outside the bag's own range instead of waiting for them."""

from __future__ import annotations

import struct
import time
from pathlib import Path
from typing import Any

import pytest
from mcap.reader import make_reader
from mcap.writer import CompressionType, Writer

from ros2lite.bag import Reader
from ros2lite.bag.metadata import read_metadata_file, write_metadata_file
from ros2lite.bag.reindex import reindex
from tests.cli.conftest import run_process

T0 = 1_700_000_000_000_000_000
YEAR_2500 = 16_725_225_600 * 10**9
STRING = 'string data\n'


def cdr(text: str) -> bytes:
    raw = text.encode() + b'\x00'
    return b'\x00\x01\x00\x00' + struct.pack('<I', len(raw)) + raw


def craft(path: Path, times: list[int], *, chunk_size: int = 1024, crcs: bool = True) -> Path:
    """An MCAP file of std_msgs/String on /t, one message per time."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, 'wb') as f:
        w = Writer(f, chunk_size=chunk_size, compression=CompressionType.NONE, enable_crcs=crcs)
        w.start(profile='ros2', library='test')
        sid = w.register_schema('std_msgs/msg/String', 'ros2msg', STRING.encode())
        cid = w.register_channel('/t', 'cdr', sid, {})
        for i, t in enumerate(times):
            w.add_message(cid, t, cdr(f'm{i:04d}'), t, i)
        w.finish()
    return path


def chunk_offsets(path: Path) -> list[tuple[int, int]]:
    with open(path, 'rb') as f:
        summary = make_reader(f).get_summary()
    assert summary is not None
    return [(c.chunk_start_offset, c.chunk_length) for c in summary.chunk_indexes]


def read_all(path: Path) -> list[str]:
    with Reader(path) as reader:
        return [m.data for _, m, _ in reader.messages()]


def test_a_flipped_byte_is_reported_and_what_precedes_it_kept(tmp_path: Path, capfd: Any) -> None:
    path = craft(tmp_path / 'b' / 'b_0.mcap', [T0 + i * 1000 for i in range(100)])
    chunks = chunk_offsets(path)
    assert len(chunks) >= 3
    start, length = chunks[1]
    data = bytearray(path.read_bytes())
    data[start + length - 10] ^= 0xFF  # inside the chunk's last message
    path.write_bytes(bytes(data))
    got = read_all(path)
    err = capfd.readouterr().err
    assert f"'{path}': the chunk at byte {start} fails its CRC check (byte " in err, err
    assert 'of its messages kept, the rest dropped; the other chunks are read' in err
    # only the damaged message is lost; every other chunk is still read, in order
    assert got == sorted(got) and len(got) == 99
    assert got[0] == 'm0000' and got[-1] == 'm0099'


def test_a_bag_truncated_inside_its_only_chunk_says_so(tmp_path: Path) -> None:
    from ros2lite.bag.writer import Writer as BagWriter

    bag = tmp_path / 'cut'
    with BagWriter(str(bag)) as w:
        for i in range(4000):
            w.write('/t', _string(f'n{i}'), T0 + i)
    [mcap] = bag.glob('*.mcap')
    size = mcap.stat().st_size
    with open(mcap, 'r+b') as f:
        f.truncate(size // 2)
    with Reader(bag) as reader:
        truncated, promised = reader.shortfalls()
        got = [m.data for _, m, _ in reader.messages()]
    n = len(got)
    assert 1000 < n < 4000 and got == [f'n{i}' for i in range(n)]  # every one before the cut
    assert (
        truncated
        == f"'{mcap}' is truncated at byte {size // 2} inside a chunk: {n} messages recovered"
    )
    assert f'metadata.yaml promises 4000 messages, {n} are readable' in promised
    info = run_process('bag', 'info', str(bag))
    assert info.code == 0 and truncated in info.err and promised in info.err


def _string(text: str) -> Any:
    from ros2lite.interfaces import get_interface

    return get_interface('std_msgs/msg/String')(data=text)


def test_a_time_outside_its_chunk_is_refused(tmp_path: Path, capfd: Any) -> None:
    """No CRCs to catch it: a log time rewritten to the year 2500 inside a chunk."""
    times = [T0 + i * 1000 for i in range(10)]
    path = craft(tmp_path / 'x_0.mcap', times, chunk_size=1 << 20, crcs=False)
    data = path.read_bytes()
    needle = struct.pack('<Q', times[5]) * 2  # log_time then publish_time
    assert data.count(needle) == 1
    path.write_bytes(data.replace(needle, struct.pack('<Q', YEAR_2500) * 2))
    got = read_all(path)
    assert 'm0005' not in got and len(got) == 9
    assert "log times outside the chunk's own range" in capfd.readouterr().err


def test_play_refuses_times_outside_the_bag_range(tmp_path: Path, ros_router: str) -> None:
    bag = tmp_path / 'late'
    craft(bag / 'late_0.mcap', [T0 + i * 1_000_000 for i in range(5)] + [YEAR_2500], chunk_size=200)
    meta = reindex(bag)
    meta.duration = 4_000_000  # what the recording really spanned: the last time is corrupt
    meta.files[0].duration = 4_000_000
    write_metadata_file(bag, meta)
    assert read_metadata_file(bag / 'metadata.yaml').duration == 4_000_000
    started = time.monotonic()
    result = run_process('bag', 'play', str(bag), '--disable-keyboard-controls')
    assert result.code == 0, result
    assert time.monotonic() - started < 30
    assert "1 message(s) have log times outside the bag's own range" in result.err


def test_play_of_topics_not_in_the_bag_is_an_error(tmp_path: Path, ros_router: str) -> None:
    bag = tmp_path / 'one'
    craft(bag / 'one_0.mcap', [T0 + i for i in range(3)])
    result = run_process('bag', 'play', str(bag), '--topics', '/nope')
    assert result.code == 1
    assert 'None of the topics to play (/nope) is in the bag; it has: /t' in result.err


# -- recovery as `mcap recover` does it: every record before the damage, said in one line ------


def one_chunk_file(
    path: Path, compression: CompressionType = CompressionType.NONE, count: int = 2000
) -> list[int]:
    """The F1 bag: 2000 strings in one chunk; returns each message's end offset in the file
    (its data ends its record), for uncompressed chunks."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, 'wb') as f:
        w = Writer(f, compression=compression, chunk_size=1 << 22)
        w.start(profile='ros2', library='x')
        sid = w.register_schema(name='std_msgs/msg/String', encoding='ros2msg', data=b'string data')
        cid = w.register_channel(topic='/s', message_encoding='cdr', schema_id=sid, metadata={})
        for i in range(count):
            w.add_message(
                channel_id=cid,
                log_time=i + 1,
                publish_time=i + 1,
                data=cdr(f'message number {i:06d}'),
            )
        w.finish()
    if compression != CompressionType.NONE:
        return []
    data = path.read_bytes()
    return [data.index(f'message number {i:06d}\0'.encode()) + 22 for i in range(2000)]


def texts(path: Path) -> list[str]:
    with Reader(path) as reader:
        return [m.data for _, m, _ in reader.messages()]


WRITTEN = [f'message number {i:06d}' for i in range(8000)]


def test_a_bag_cut_inside_its_only_chunk_keeps_every_whole_record(
    tmp_path: Path, ros_context: Any
) -> None:
    from ros2lite.bag.player import Player, PlayOptions
    from ros2lite.node import Node

    ends = one_chunk_file(tmp_path / 'whole' / 'whole_0.mcap')
    cut = tmp_path / 'cut' / 'cut_0.mcap'
    cut.parent.mkdir()
    cut.write_bytes((tmp_path / 'whole' / 'whole_0.mcap').read_bytes()[:30000])
    whole = sum(end <= 30000 for end in ends)
    assert whole > 400
    line = f"'{cut}' is truncated at byte 30000 inside a chunk: {whole} messages recovered"
    info = run_process('bag', 'info', str(cut.parent))
    assert info.code == 0 and line in info.err, info
    assert f'Messages:          {whole}\n' in info.out
    assert texts(cut.parent) == WRITTEN[:whole]
    node = Node('recovery_test', context=ros_context, enable_rosout=False)
    try:
        player = Player(node, Reader(cut.parent), PlayOptions(rate=1000.0))
        player.play()
        assert player.published == whole
    finally:
        node.destroy_node()
    # reindex writes a whole bag that rosbag2's and Foxglove's readers open
    result = run_process('bag', 'reindex', str(cut.parent))
    assert result.code == 0 and line in result.err, result
    from mcap.reader import make_reader
    from rosbags.rosbag2 import Reader as RosbagsReader

    with RosbagsReader(cut.parent) as bag:
        assert bag.message_count == whole
        assert [bytes(raw)[8:-1].decode() for _, _, raw in bag.messages()] == WRITTEN[:whole]
    with open(cut, 'rb') as f:
        assert sum(1 for _ in make_reader(f).iter_messages()) == whole
    assert texts(cut.parent) == WRITTEN[:whole]


def test_cuts_and_flipped_bytes_at_random_offsets_keep_exactly_what_precedes_them(
    tmp_path: Path,
) -> None:
    import random

    src = tmp_path / 'src_0.mcap'
    ends = one_chunk_file(src)
    data = src.read_bytes()
    rng = random.Random(28)
    for k, at in enumerate(sorted(rng.sample(range(9, len(data)), 20))):
        path = tmp_path / f'cut{k}' / f'cut{k}_0.mcap'
        path.parent.mkdir()
        path.write_bytes(data[:at])
        # a cut in the summary after the chunk keeps everything
        assert texts(path) == WRITTEN[: sum(end <= at for end in ends)], at
    first, last = ends[0] - 60, ends[-1]  # the chunk's records
    for k, at in enumerate(rng.sample(range(first, last), 20)):
        path = tmp_path / f'flip{k}' / f'flip{k}_0.mcap'
        path.parent.mkdir()
        damaged = bytearray(data)
        damaged[at] ^= 1 << rng.randrange(8)
        path.write_bytes(bytes(damaged))
        assert texts(path) == WRITTEN[: sum(end <= at for end in ends)], at


@pytest.mark.parametrize('compression', [CompressionType.ZSTD, CompressionType.LZ4])
def test_a_compressed_chunk_cut_short_gives_a_prefix_of_what_was_written(
    tmp_path: Path, compression: CompressionType
) -> None:
    src = tmp_path / 'src_0.mcap'
    one_chunk_file(src, compression, count=8000)  # zstd inflates whole blocks of 128 KiB
    data = src.read_bytes()
    [(start, length)] = chunk_offsets(src)
    got = []
    for k, at in enumerate(range(start + 100, start + length, length // 8)):
        path = tmp_path / f'cut{k}' / f'cut{k}_0.mcap'
        path.parent.mkdir()
        path.write_bytes(data[:at])
        got.append(len(texts(path)))
        assert texts(path) == WRITTEN[: got[-1]]
    assert got == sorted(got) and any(0 < n < 8000 for n in got), got  # partly inflated


def test_a_flipped_bit_anywhere_never_crashes_or_invents_a_message(tmp_path: Path) -> None:
    """Header, chunk header, indexes, summary, footer: whatever a flipped bit hits, reading
    gives messages that were written, in order (some may be lost, none made up)."""
    import random

    src = tmp_path / 'src_0.mcap'
    one_chunk_file(src)
    data = src.read_bytes()
    rng = random.Random(7)
    for k in range(30):
        at = rng.randrange(len(data))
        path = tmp_path / f'flip{k}' / f'flip{k}_0.mcap'
        path.parent.mkdir()
        damaged = bytearray(data)
        damaged[at] ^= 1 << rng.randrange(8)
        path.write_bytes(bytes(damaged))
        with Reader(path.parent) as reader:
            got = [m.data if hasattr(m, 'data') else m for _, m, _ in reader.messages()]
        written = iter(WRITTEN)
        assert all(text in written for text in got), at


def _with_rosbag2_record(path: Path, metadata_text: str, *, summary: bool = True) -> Path:
    """A bag of 100 messages with a `rosbag2` metadata record, as rosbag2 writes it."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path, 'wb') as f:
        w = Writer(
            f, chunk_size=1024, compression=CompressionType.NONE, use_summary_offsets=summary
        )
        w.start(profile='ros2', library='test')
        sid = w.register_schema('std_msgs/msg/String', 'ros2msg', STRING.encode())
        cid = w.register_channel('/t', 'cdr', sid, {})
        for i in range(100):
            w.add_message(cid, T0 + i, cdr(f'm{i:04d}'), T0 + i, i)
        w.add_metadata('rosbag2', {'serialized_metadata': metadata_text, 'ROS_DISTRO': 'jazzy'})
        w.finish()
    return path


def test_a_flipped_byte_in_the_metadata_record_loses_no_message(tmp_path: Path) -> None:
    """R5-B6: a byte of the rosbag2 metadata record made invalid UTF-8 failed info, play and
    reindex with a utf-8 codec line, and the 100 intact messages were unreadable; now the
    damage is named and every message read."""
    marker = 'ros2lite-flip-me'
    path = _with_rosbag2_record(tmp_path / 'b' / 'b_0.mcap', f'version: 9\n# {marker}\n')
    data = bytearray(path.read_bytes())
    spots = [i for i in range(len(data)) if data.startswith(marker.encode(), i)]
    assert spots  # the record and nowhere else (no summary copy of metadata)
    for at in spots:
        data[at] = 0xFF  # not UTF-8
    path.write_bytes(bytes(data))
    with Reader(path.parent) as reader:
        problems = reader.shortfalls()
        got = [m.data for _, m, _ in reader.messages()]
    assert got == [f'm{i:04d}' for i in range(100)]
    assert any('rosbag2 metadata record at byte' in p and 'damaged' in p for p in problems), (
        problems
    )


def test_an_empty_mcap_and_a_fifo_are_named_not_waited_on(tmp_path: Path) -> None:
    """R5-B6/B7: a zero-length .mcap said `is not an MCAP file ()`; a metadata.yaml naming a
    FIFO blocked info and play silently. Only regular files are opened."""
    import os

    from ros2lite.bag.errors import BagError

    empty = tmp_path / 'e'
    empty.mkdir()
    (empty / 'e_0.mcap').write_bytes(b'')
    with pytest.raises(BagError, match=r'is empty \(0 bytes\)'):
        Reader(empty).summary()
    fifo = tmp_path / 'f'
    fifo.mkdir()
    os.mkfifo(fifo / 'f_0.mcap')
    started = time.monotonic()
    with pytest.raises(BagError, match='not a regular file'):
        Reader(fifo / 'f_0.mcap').summary()
    assert time.monotonic() - started < 2
