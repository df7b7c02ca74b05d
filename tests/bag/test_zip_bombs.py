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
