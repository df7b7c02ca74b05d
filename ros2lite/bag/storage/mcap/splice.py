"""An MCAP file made of part of another: the chunks wholly wanted (every message inside the time
range, on kept channels only) are copied as bytes with their message indexes, never inflated or
decoded; only the chunks at the edges of the range, or mixing kept and dropped channels, are
inflated and their kept messages written into new chunks. What `bag cut` and `bag filter` stand
on: cutting a minute out of a gigabyte costs about the minute's bytes, not the gigabyte's.

The copy keeps the source's channel and schema ids (the copied chunks name them), writes the
kept schemas and channels once at the head of the data section, and ends in a complete summary
(schemas, channels, statistics, chunk and metadata indexes, summary offsets).
"""

from __future__ import annotations

import os
import struct
import zlib
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import IO, TYPE_CHECKING

import lz4.frame
import zstandard
from mcap.data_stream import RecordBuilder
from mcap.reader import SeekingReader
from mcap.records import (
    Channel,
    Chunk,
    ChunkIndex,
    DataEnd,
    Header,
    McapRecord,
    Message,
    MessageIndex,
    Metadata,
    MetadataIndex,
    Schema,
    Statistics,
    SummaryOffset,
)

from ros2lite.bag.errors import BagError
from ros2lite.bag.storage.mcap.scan import read_chunk_at
from ros2lite.util.files import UnsafePathError, create_new

if TYPE_CHECKING:
    from mcap.summary import Summary

__all__ = ["SpliceResult", "splice"]

_MAGIC = b"\x89MCAP0\r\n"
_MESSAGE, _CHUNK, _MESSAGE_INDEX, _DATA_END = 5, 6, 7, 15
_COPY_STEP = 64 << 20  # bytes per copy_file_range call
_MAX_INDEX_BYTES = 64 << 20  # the message indexes of one chunk read to count its messages


@dataclass
class SpliceResult:
    """What one spliced file holds, and how it was made."""

    counts: dict[str, int] = field(default_factory=dict)  # topic → messages
    message_count: int = 0
    start: int | None = None  # first log time (ns)
    end: int | None = None
    chunks_copied: int = 0  # chunks copied as bytes
    chunks_rewritten: int = 0  # source chunks inflated for some of their messages
    problems: list[str] = field(default_factory=list)  # damaged source chunks, one line each

    def note(self, topic: str, count: int, first: int, last: int) -> None:
        """Count `count` messages of `topic` logged from `first` to `last`."""
        if not count:
            return
        self.counts[topic] = self.counts.get(topic, 0) + count
        self.message_count += count
        self.start = first if self.start is None else min(self.start, first)
        self.end = last if self.end is None else max(self.end, last)


class _Out:
    """The new file: unbuffered writes at a known position (whole records at a time)."""

    def __init__(self, path: str) -> None:

        try:
            self.fd = create_new(path)
        except (OSError, UnsafePathError) as e:
            raise BagError(f"Cannot write '{path}': {e}") from None
        self.pos = 0

    def write(self, data: bytes | bytearray) -> int:
        at = self.pos
        view = memoryview(data)
        done = 0
        while done < len(view):
            done += os.write(self.fd, view[done:])
        self.pos += len(view)
        return at

    def copy_from(self, src: IO[bytes], offset: int, length: int) -> int:
        """Copy `length` bytes at `offset` of `src` in the kernel where it can."""
        at = self.pos
        fd_in = src.fileno()
        done = 0
        try:
            while done < length:
                n = os.copy_file_range(
                    fd_in, self.fd, min(_COPY_STEP, length - done), offset + done
                )
                if n <= 0:
                    break
                done += n
        except (AttributeError, OSError):
            pass  # another file system or kernel: copied by hand below
        while done < length:
            src.seek(offset + done)
            piece = src.read(min(_COPY_STEP, length - done))
            if not piece:
                raise BagError(f"'{getattr(src, 'name', 'the bag')}' ends inside a chunk")
            os.write(self.fd, piece)
            done += len(piece)
        self.pos += length
        return at

    def close(self) -> None:
        os.close(self.fd)


def _bytes(record: McapRecord) -> bytes:

    builder = RecordBuilder()
    record.write(builder)
    data: bytes = builder.end()
    return data


class _ChunkBuilder:
    """Messages gathered into a new chunk, with its message indexes."""

    def __init__(self, compression: str, chunk_size: int) -> None:
        self.compression = compression
        self.chunk_size = chunk_size
        self.records = bytearray()
        self.index: dict[int, list[tuple[int, int]]] = {}
        self.start = 0
        self.end = 0

    def add(
        self, channel_id: int, sequence: int, log_time: int, publish_time: int, data: bytes
    ) -> None:
        if not self.records:
            self.start = self.end = log_time
        self.index.setdefault(channel_id, []).append((log_time, len(self.records)))
        self.records += struct.pack(
            "<BQHIQQ", _MESSAGE, 22 + len(data), channel_id, sequence, log_time, publish_time
        )
        self.records += data
        self.start = min(self.start, log_time)
        self.end = max(self.end, log_time)

    def full(self) -> bool:
        return len(self.records) >= self.chunk_size

    def finish(self, out: _Out) -> ChunkIndex | None:
        """Write the chunk and its message indexes; its index entry."""

        if not self.records:
            return None
        raw = bytes(self.records)
        if self.compression == "zstd":
            data = zstandard.ZstdCompressor().compress(raw)
        elif self.compression == "lz4":
            data = lz4.frame.compress(raw)
        else:
            data = raw
        chunk = _bytes(
            Chunk(
                compression=self.compression,
                data=data,
                message_start_time=self.start,
                message_end_time=self.end,
                uncompressed_crc=zlib.crc32(raw),
                uncompressed_size=len(raw),
            )
        )
        at = out.write(chunk)
        offsets: dict[int, int] = {}
        index_start = out.pos
        for cid in sorted(self.index):
            offsets[cid] = out.write(_bytes(MessageIndex(cid, self.index[cid])))
        entry = ChunkIndex(
            message_start_time=self.start,
            message_end_time=self.end,
            chunk_start_offset=at,
            chunk_length=len(chunk),
            message_index_offsets=offsets,
            message_index_length=out.pos - index_start,
            compression=self.compression,
            compressed_size=len(data),
            uncompressed_size=len(raw),
        )
        self.records = bytearray()
        self.index = {}
        return entry


def _index_counts(data: bytes, keep: set[int]) -> dict[int, tuple[int, int, int]] | None:
    """(count, first, last log time) per channel from a chunk's message index records; None
    when they are not what the chunk index says (then the chunk is not copied blindly)."""
    out: dict[int, tuple[int, int, int]] = {}
    pos = 0
    while pos < len(data):
        if len(data) - pos < 15 or data[pos] != _MESSAGE_INDEX:
            return None
        (length, cid, n) = struct.unpack_from("<QHI", data, pos + 1)
        if length != 6 + n or n % 16 or pos + 9 + length > len(data):
            return None
        if cid not in keep:
            return None
        if n:
            first = last = struct.unpack_from("<Q", data, pos + 15)[0]
            for k in range(n // 16):
                (t,) = struct.unpack_from("<Q", data, pos + 15 + 16 * k)
                first, last = min(first, t), max(last, t)
            out[cid] = (n // 16, first, last)
        pos += 9 + length
    return out


def splice(
    source: str,
    dest: str,
    *,
    keep: Callable[[Channel], bool],
    start: int | None = None,
    stop: int | None = None,
    metadata: Callable[[SpliceResult], dict[str, str]] | None = None,
    library: str = "ros2lite",
    chunk_size: int = 768 * 1024,
) -> SpliceResult:
    """Write to `dest` (a new file) the messages of the MCAP file `source` on channels `keep`
    accepts, with `start <= log_time < stop`. `metadata` gives the `rosbag2` record's map once
    the messages are written. Raises BagError for a source without a summary (the caller reads
    it message by message instead)."""

    try:
        src = open(source, "rb")  # noqa: SIM115 - closed in the finally below
    except OSError as e:
        raise BagError(f"Cannot open '{source}': {e.strerror or e}") from None
    try:
        try:
            reader = SeekingReader(src)
            header = reader.get_header()
            summary = reader.get_summary()
        except Exception as e:
            raise BagError(
                f"'{source}' has no readable summary ({e or type(e).__name__})"
            ) from None
        if summary is None or summary.statistics is None or not summary.chunk_indexes:
            if (
                summary is not None
                and summary.statistics is not None
                and not summary.statistics.message_count
            ):
                pass  # an empty file: nothing to copy, an empty file is written
            else:
                raise BagError(f"'{source}' has no chunk index (not written to its end)")
        return _splice(
            src, summary, header.profile, dest, keep, start, stop, metadata, library, chunk_size
        )
    finally:
        src.close()


def _splice(
    src: IO[bytes],
    summary: Summary,
    profile: str,
    dest: str,
    keep: Callable[[Channel], bool],
    start: int | None,
    stop: int | None,
    metadata: Callable[[SpliceResult], dict[str, str]] | None,
    library: str,
    chunk_size: int,
) -> SpliceResult:

    channels = {cid: c for cid, c in summary.channels.items() if keep(c)}
    schemas: dict[int, Schema] = {
        c.schema_id: summary.schemas[c.schema_id]
        for c in channels.values()
        if c.schema_id in summary.schemas
    }
    kept_ids = set(channels)
    result = SpliceResult(counts=dict.fromkeys((c.topic for c in channels.values()), 0))
    per_channel: dict[int, int] = dict.fromkeys(channels, 0)
    lo = -1 if start is None else start
    hi = 2**64 if stop is None else stop  # exclusive
    size = src.seek(0, os.SEEK_END)
    data_end = _data_end(src, size)
    strict = len(channels) < len(summary.channels)  # records of dropped channels may hide
    out = _Out(dest)
    indexes: list[ChunkIndex] = []
    try:
        out.write(_MAGIC)
        out.write(_bytes(Header(profile=profile, library=library)))
        for schema in schemas.values():
            out.write(_bytes(schema))
        for channel in channels.values():
            out.write(_bytes(channel))
        builder: _ChunkBuilder | None = None
        for index in sorted(summary.chunk_indexes, key=lambda c: c.chunk_start_offset):
            if index.message_end_time < lo or index.message_start_time >= hi:
                continue
            present = set(index.message_index_offsets)
            if present and not present & kept_ids:
                continue
            counts = None
            inside = lo <= index.message_start_time and index.message_end_time < hi
            if inside and present and present <= kept_ids:
                counts = _copyable(src, index, kept_ids, data_end)
                if counts is not None and strict and _strays(src, index, kept_ids, set(schemas)):
                    counts = None
            if counts is not None and builder is not None and builder.records:
                entry = builder.finish(out)
                if entry is not None:
                    indexes.append(entry)
            if counts is not None:
                at = out.copy_from(
                    src, index.chunk_start_offset, index.chunk_length + index.message_index_length
                )
                delta = at - index.chunk_start_offset
                indexes.append(_moved(index, delta))
                result.chunks_copied += 1
                for cid, (n, first, last) in counts.items():
                    per_channel[cid] += n
                    result.note(channels[cid].topic, n, first, last)
                continue
            # an edge chunk, or one mixing dropped channels: its kept messages re-encoded
            kept: list[McapRecord] = []
            problem = read_chunk_at(src, index.chunk_start_offset, kept)
            if problem is not None:
                result.problems.append(
                    f"the chunk at byte {index.chunk_start_offset} {problem}: "
                    f"{sum(isinstance(r, Message) for r in kept)} of its messages kept"
                )
            result.chunks_rewritten += 1
            if builder is None:
                builder = _ChunkBuilder(index.compression, chunk_size)
            builder.compression = (
                index.compression if index.compression in ("", "zstd", "lz4") else "zstd"
            )
            for record in kept:
                if not isinstance(record, Message) or record.channel_id not in kept_ids:
                    continue
                t = record.log_time
                if not (lo <= t < hi and index.message_start_time <= t <= index.message_end_time):
                    continue
                builder.add(record.channel_id, record.sequence, t, record.publish_time, record.data)
                per_channel[record.channel_id] += 1
                result.note(channels[record.channel_id].topic, 1, t, t)
                if builder.full():
                    entry = builder.finish(out)
                    if entry is not None:
                        indexes.append(entry)
        if builder is not None:
            entry = builder.finish(out)
            if entry is not None:
                indexes.append(entry)
        metadata_indexes = []
        if metadata is not None:
            blob = _bytes(Metadata(name="rosbag2", metadata=metadata(result)))
            at = out.write(blob)
            metadata_indexes.append(MetadataIndex(offset=at, length=len(blob), name="rosbag2"))
        out.write(_bytes(DataEnd(data_section_crc=0)))
        summary_at = out.pos
        body = bytearray()
        offsets: list[SummaryOffset] = []

        def group(opcode: int, records: Iterable[McapRecord]) -> None:
            begin = len(body)
            for r in records:
                body.extend(_bytes(r))
            if len(body) > begin:
                offsets.append(SummaryOffset(opcode, summary_at + begin, len(body) - begin))

        group(0x03, schemas.values())
        group(0x04, channels.values())
        group(
            0x0B,
            [
                Statistics(
                    message_count=result.message_count,
                    schema_count=len(schemas),
                    channel_count=len(channels),
                    attachment_count=0,
                    metadata_count=len(metadata_indexes),
                    chunk_count=len(indexes),
                    message_start_time=result.start or 0,
                    message_end_time=result.end or 0,
                    channel_message_counts=per_channel,
                )
            ],
        )
        group(0x08, indexes)
        group(0x0D, metadata_indexes)
        offsets_at = summary_at + len(body)
        for o in offsets:
            body.extend(_bytes(o))
        footer_head = struct.pack("<BQQQ", 0x02, 20, summary_at, offsets_at)
        crc = zlib.crc32(footer_head, zlib.crc32(body))
        out.write(body)
        out.write(footer_head + struct.pack("<I", crc) + _MAGIC)
    except BaseException:
        out.close()
        os.unlink(dest)
        raise
    out.close()
    return result


def _data_end(src: IO[bytes], size: int) -> int:
    """Where the data section ends (the footer's summary start): no chunk copied on a hostile
    index's word reaches past it."""
    if size < 8 + 29 + 8:
        return size
    src.seek(size - 8 - 29)
    footer = src.read(29)
    if footer[0] != 0x02:
        return size
    (at,) = struct.unpack_from("<Q", footer, 9)
    return at if 0 < at <= size else size


def _copyable(
    src: IO[bytes], index: ChunkIndex, keep: set[int], data_end: int
) -> dict[int, tuple[int, int, int]] | None:
    """Per-channel counts of a chunk that can be copied as it is: its record is where its index
    says, of the length it says, followed by message indexes of kept channels only. None when
    anything disagrees (the chunk is then read and checked instead)."""
    at, length, mlen = index.chunk_start_offset, index.chunk_length, index.message_index_length
    # an index entry is 16 bytes for a message record of at least 31: more index than that
    # is a lie, and is not read into memory on its word
    most = min(_MAX_INDEX_BYTES, 16 * (index.uncompressed_size // 31 + 1) + 4096)
    if at < 8 or length < 9 or mlen < 0 or at + length + mlen > data_end or mlen > most:
        return None
    src.seek(at)
    head = src.read(9)
    if len(head) < 9 or head[0] != _CHUNK or struct.unpack_from("<Q", head, 1)[0] + 9 != length:
        return None
    src.seek(at + length)
    counts = _index_counts(src.read(mlen), keep)
    if counts is None or not counts:
        return None
    first = min(c[1] for c in counts.values())
    last = max(c[2] for c in counts.values())
    if first < index.message_start_time or last > index.message_end_time:
        return None
    return counts


def _strays(src: IO[bytes], index: ChunkIndex, channels: set[int], schemas: set[int]) -> bool:
    """Whether a chunk registers a channel or schema that is not kept (a filter must not copy
    a dropped topic's records along): its records inflated, their message data skipped."""

    records: list[McapRecord] = []
    if read_chunk_at(src, index.chunk_start_offset, records, headers_only=True) is not None:
        return True
    return any(
        (isinstance(r, Channel) and r.id not in channels)
        or (isinstance(r, Schema) and r.id not in schemas)
        for r in records
    )


def _moved(index: ChunkIndex, delta: int) -> ChunkIndex:

    return ChunkIndex(
        message_start_time=index.message_start_time,
        message_end_time=index.message_end_time,
        chunk_start_offset=index.chunk_start_offset + delta,
        chunk_length=index.chunk_length,
        message_index_offsets={c: o + delta for c, o in index.message_index_offsets.items()},
        message_index_length=index.message_index_length,
        compression=index.compression,
        compressed_size=index.compressed_size,
        uncompressed_size=index.uncompressed_size,
    )
