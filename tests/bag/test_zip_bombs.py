"""Zip-bomb chunks (R-N1/N2/N4): a chunk is inflated piece by piece and never past the size
it declares, so a few KiB of file cost neither hundreds of MB nor half a minute of silence;
what was refused is said in one line."""

from __future__ import annotations

import resource
import struct
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import lz4.frame
import pytest
import zstandard
from mcap.data_stream import RecordBuilder
from mcap.records import Channel, Chunk, DataEnd, Footer, Header, Schema

from ros2lite.bag import Reader

MAGIC = b'\x89MCAP0\r\n'
N = 256 << 20  # what the bomb inflates to


def compress(compression: str, pieces: list[bytes]) -> bytes:
    """Compressed piece by piece: the test never holds what the bomb inflates to."""
    if compression == 'zstd':
        z = zstandard.ZstdCompressor(level=3).compressobj()
        return b''.join(z.compress(p) for p in pieces) + z.flush()
    lz = lz4.frame.LZ4FrameCompressor()
    return lz.begin() + b''.join(lz.compress(p) for p in pieces) + lz.flush()


def bomb(path: Path, compression: str, inflated: bytes | None, declared: int, crc: int = 0) -> Path:
    """Header, Schema, Channel, one Chunk, DataEnd, Footer: no summary."""
    zeros = b'\0' * (1 << 20)
    data = compress(compression, [inflated] if inflated else [zeros] * (N >> 20))
    b = RecordBuilder()
    Header(profile='ros2', library='bomb').write(b)
    Schema(id=1, name='std_msgs/msg/String', encoding='ros2msg', data=b'string data').write(b)
    Channel(id=1, topic='/s', message_encoding='cdr', metadata={}, schema_id=1).write(b)
    Chunk(
        compression=compression,
        data=data,
        message_start_time=1,
        message_end_time=10**6,
        uncompressed_crc=crc,
        uncompressed_size=declared,
    ).write(b)
    DataEnd(data_section_crc=0).write(b)
    Footer(summary_start=0, summary_offset_start=0, summary_crc=0).write(b)
    path.mkdir()
    (path / f'{path.name}_0.mcap').write_bytes(MAGIC + b.end() + MAGIC)
    return path


def messages(n: int) -> bytes:
    """n message records on channel 1, as a chunk holds them."""
    out = []
    for i in range(n):
        text = f'm{i:07d}'.encode() + b'\0'
        body = (
            struct.pack('<HIQQ', 1, i, i + 1, i + 1)
            + b'\0\1\0\0'
            + struct.pack('<I', len(text))
            + text
        )
        out.append(struct.pack('<BQ', 5, len(body)) + body)
    return b''.join(out)


def info(bag: Path) -> tuple[str, float]:
    """`bag info` as a process allowed less address space than the bomb inflates to (it
    needs ~100 MB): its stderr and seconds."""

    def limit() -> None:
        resource.setrlimit(resource.RLIMIT_AS, (N, N))

    started = time.monotonic()
    proc = subprocess.run(
        [sys.executable, '-m', 'ros2lite', 'bag', 'info', str(bag)],
        capture_output=True,
        text=True,
        preexec_fn=limit,
        timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    return proc.stderr, time.monotonic() - started


@pytest.mark.parametrize('compression', ['zstd', 'lz4'])
def test_a_chunk_of_zeros_is_refused_at_once_in_one_line(tmp_path: Path, compression: str) -> None:
    bag = bomb(tmp_path / 'b', compression, None, N)
    assert (bag / 'b_0.mcap').stat().st_size < 2 << 20
    err, seconds = info(bag)
    lines = err.splitlines()
    assert len(lines) == 1, err
    assert 'holds a record of unknown kind (0): 0 of its messages kept' in lines[0], err
    assert seconds < 15  # was 24 s of silence (and ~281 MB)


@pytest.mark.parametrize('compression', ['zstd', 'lz4'])
def test_a_chunk_inflating_past_its_declared_size_stops_there(
    tmp_path: Path, compression: str
) -> None:
    records = messages(100_000)  # ~5 MB of valid records, declared as 1 KiB
    bag = bomb(tmp_path / 'b', compression, records, 1024)
    whole = 0
    while (end := sum(len(messages(1)) for _ in range(whole + 1))) <= 1024:
        whole += 1
    assert 0 < whole < 100
    with Reader(bag) as reader:
        [line] = reader.shortfalls()
        got = [m.data for _, m, _ in reader.messages()]
    assert got == [f'm{i:07d}' for i in range(whole)]
    assert f': {whole} of its messages kept, the rest dropped' in line
    assert 'inflates past its declared 1024 bytes' in line or 'running past its end' in line
    del end


@pytest.mark.parametrize('compression', ['zstd', 'lz4'])
def test_a_checksummed_chunk_is_not_inflated_past_its_declared_size(
    tmp_path: Path, compression: str
) -> None:
    """The CRC is checked before a record is trusted: that pass, too, stops at the size the
    chunk declares instead of inflating (and checksumming) all of it."""
    bag = bomb(tmp_path / 'b', compression, None, 1024, crc=0x12345678)
    err, seconds = info(bag)
    assert 'inflates past its declared 1024 bytes: 0 of its messages kept' in err, err
    assert seconds < 15


def _record(op: int, body: bytes) -> bytes:
    return struct.pack('<BQ', op, len(body)) + body


def _empty_message() -> bytes:
    """The smallest message record there is: channel 1, no data (31 bytes)."""
    return _record(5, struct.pack('<HIQQ', 1, 0, 1, 1))


def test_millions_of_identical_tiny_records_are_one_line(tmp_path: Path) -> None:
    """R5-B1: 22 KB of zstd holding 256 MiB of 31-byte empty messages took `bag info` 24 s and
    1.2 GB; a chunk may hold no more records than a recording's compressor could have made
    of its bytes, so the rest is refused in one line, at once."""
    one = _empty_message()
    count = N // len(one)
    per_piece = (1 << 20) // len(one)
    pieces = [one * per_piece] * (count // per_piece)
    bag = bomb(tmp_path / 'b', 'zstd', None, len(one) * per_piece * len(pieces))
    # bomb() writes zeros when given no records: write this chunk's records instead
    data = compress('zstd', pieces)
    b = RecordBuilder()
    Header(profile='ros2', library='bomb').write(b)
    Schema(id=1, name='std_msgs/msg/String', encoding='ros2msg', data=b'string data').write(b)
    Channel(id=1, topic='/s', message_encoding='cdr', metadata={}, schema_id=1).write(b)
    Chunk(
        compression='zstd',
        data=data,
        message_start_time=1,
        message_end_time=1,
        uncompressed_crc=0,
        uncompressed_size=len(one) * per_piece * len(pieces),
    ).write(b)
    DataEnd(data_section_crc=0).write(b)
    Footer(summary_start=0, summary_offset_start=0, summary_crc=0).write(b)
    (bag / 'b_0.mcap').write_bytes(MAGIC + b.end() + MAGIC)
    assert (bag / 'b_0.mcap').stat().st_size < 64 << 10
    err, seconds = info(bag)
    lines = err.splitlines()
    assert len(lines) == 1 and 'a decompression bomb' in lines[0], err
    assert seconds < 10  # was 24-45 s
    kept = int(lines[0].split(': ')[-1].split(' of its')[0])
    assert 0 < kept <= 4096 + len(data)


def test_one_huge_record_without_summary_is_counted_without_holding_it(tmp_path: Path) -> None:
    """R5-B2: one 256 MiB record, no summary: `bag info` held it whole (790 MB); counting a
    message needs its header only, so info runs in a process allowed less than the record."""
    body = struct.pack('<HIQQ', 1, 0, 5, 5) + b'\0\1\0\0' + struct.pack('<I', 1) + b'\0'
    record_len = 22 + N
    head = struct.pack('<BQ', 5, record_len) + body
    pieces = [head, *([b'\0' * (1 << 20)] * (N >> 20))]
    size = len(head) + N - (len(body) - 22)
    pieces[-1] = pieces[-1][: len(pieces[-1]) - (len(body) - 22)]
    bag = bomb(tmp_path / 'b', 'zstd', None, size)
    data = compress('zstd', pieces)
    b = RecordBuilder()
    Header(profile='ros2', library='bomb').write(b)
    Schema(id=1, name='std_msgs/msg/String', encoding='ros2msg', data=b'string data').write(b)
    Channel(id=1, topic='/s', message_encoding='cdr', metadata={}, schema_id=1).write(b)
    Chunk(
        compression='zstd',
        data=data,
        message_start_time=5,
        message_end_time=5,
        uncompressed_crc=0,
        uncompressed_size=size,
    ).write(b)
    DataEnd(data_section_crc=0).write(b)
    Footer(summary_start=0, summary_offset_start=0, summary_crc=0).write(b)
    (bag / 'b_0.mcap').write_bytes(MAGIC + b.end() + MAGIC)
    err, seconds = info(bag)  # RLIMIT_AS of 256 MiB: holding the record would fail
    assert 'bomb' not in err, err
    proc = subprocess.run(
        [sys.executable, '-m', 'ros2lite', 'bag', 'info', str(bag)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert 'Messages:          1\n' in proc.stdout, proc.stdout
    assert seconds < 10


def test_a_chunk_behind_many_indexes_is_read_once(tmp_path: Path) -> None:
    """R5-B3: one chunk named by 10,000 chunk indexes made the reader yield every message
    10,000 times; each chunk is now read once, and the repetition is said in one line."""
    import zlib

    from mcap.records import ChunkIndex, Statistics

    def rec(record: Any) -> bytes:
        b = RecordBuilder()
        record.write(b)
        return bytes(b.end())

    raw = messages(1000)
    data = compress('zstd', [raw])
    schema = Schema(id=1, name='std_msgs/msg/String', encoding='ros2msg', data=b'string data')
    channel = Channel(id=1, topic='/s', message_encoding='cdr', metadata={}, schema_id=1)
    out = bytearray(MAGIC) + rec(Header(profile='ros2', library='dup')) + rec(schema)
    out += rec(channel)
    chunk = rec(
        Chunk(
            compression='zstd',
            data=data,
            message_start_time=1,
            message_end_time=1000,
            uncompressed_crc=zlib.crc32(raw),
            uncompressed_size=len(raw),
        )
    )
    chunk_at = len(out)
    out += chunk + rec(DataEnd(data_section_crc=0))
    summary_start = len(out)
    out += rec(schema) + rec(channel)
    out += rec(
        Statistics(
            message_count=1000,
            schema_count=1,
            channel_count=1,
            attachment_count=0,
            metadata_count=0,
            chunk_count=10_000,
            message_start_time=1,
            message_end_time=1000,
            channel_message_counts={1: 1000},
        )
    )
    index = rec(
        ChunkIndex(
            message_start_time=1,
            message_end_time=1000,
            chunk_start_offset=chunk_at,
            chunk_length=len(chunk),
            message_index_offsets={},
            message_index_length=0,
            compression='zstd',
            compressed_size=len(data),
            uncompressed_size=len(raw),
        )
    )
    out += index * 10_000
    out += rec(Footer(summary_start=summary_start, summary_offset_start=0, summary_crc=0))
    out += MAGIC
    bag = tmp_path / 'dup'
    bag.mkdir()
    (bag / 'dup_0.mcap').write_bytes(bytes(out))
    started = time.monotonic()
    with Reader(bag) as reader:
        got = [m.data for _, m, _ in reader.messages()]
    assert got == [f'm{i:07d}' for i in range(1000)]  # each once, in order
    assert time.monotonic() - started < 20  # was 167 s for 10,000,000 messages


def test_a_legitimate_huge_message_reads_in_about_the_time_of_reading_it(tmp_path: Path) -> None:
    """R5-B4: a real 64 MiB message in a zstd chunk with a summary: its record was grown by
    `bytes +=` piece after piece (quadratic); now inflated once and copied once."""
    from mcap.writer import CompressionType, Writer

    size = 64 << 20
    text = b'a' * (size - 1) + b'\0'
    bag = tmp_path / 'big'
    bag.mkdir()
    with open(bag / 'big_0.mcap', 'wb') as f:
        writer = Writer(f, compression=CompressionType.ZSTD)
        writer.start(profile='ros2', library='test')
        sid = writer.register_schema('std_msgs/msg/String', 'ros2msg', b'string data')
        cid = writer.register_channel('/big', 'cdr', sid)
        writer.add_message(
            cid, log_time=1, publish_time=1, data=b'\0\1\0\0' + struct.pack('<I', size) + text
        )
        writer.finish()
    # the floor on this machine now: inflating the same data once with zstd
    packed = compress('zstd', [text])
    floor_start = time.monotonic()
    zstandard.ZstdDecompressor().decompress(packed, max_output_size=size)
    floor = time.monotonic() - floor_start
    started = time.monotonic()
    with Reader(bag) as reader:
        [(_, message, _, _)] = list(reader.raw_messages())
    seconds = time.monotonic() - started
    assert len(message) == size + 8
    # quadratic growth cost 33 s at 256 MiB; linear reading is a small multiple of the floor
    assert seconds < 10 * floor + 2, (seconds, floor)
