"""Crafted bags (written with the `mcap` package, then damaged): a corrupt chunk is reported
with file and offset and skipped, a truncated bag says what it promised and what is readable,
and playback refuses log times outside the bag's own range instead of waiting for them."""

from __future__ import annotations

import struct
import time
from pathlib import Path
from typing import Any

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


def test_a_flipped_byte_is_reported_and_its_chunk_skipped(tmp_path: Path, capfd: Any) -> None:
    path = craft(tmp_path / 'b' / 'b_0.mcap', [T0 + i * 1000 for i in range(100)])
    chunks = chunk_offsets(path)
    assert len(chunks) >= 3
    start, length = chunks[1]
    data = bytearray(path.read_bytes())
    data[start + length - 10] ^= 0xFF  # inside the chunk's last message
    path.write_bytes(bytes(data))
    got = read_all(path)
    err = capfd.readouterr().err
    assert f"'{path}': corrupt chunk at offset {start} skipped" in err, err
    assert 'crc validation failed' in err
    # every other chunk is still read, in order
    assert got and got == sorted(got) and len(got) < 100
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
        [problem] = reader.shortfalls()
    assert 'metadata.yaml promises 4000 messages, 0 are readable' in problem
    info = run_process('bag', 'info', str(bag))
    assert info.code == 0 and 'promises 4000 messages, 0 are readable' in info.err


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
