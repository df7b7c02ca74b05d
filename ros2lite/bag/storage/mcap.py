"""The `mcap` storage plugin: rosbag2's MCAP layout on top of the `mcap` package.

Writing: profile `ros2`, chunked, every index, statistics and summary (rosbag2's defaults), one
`ros2msg` schema per type, one channel per topic carrying `offered_qos_profiles` and
`topic_type_hash`, and `rosbag2` metadata records. The file is written without a user-space
buffer, so each finished chunk is in the OS the moment the writer lets go of it: a recorder
killed outright leaves every complete chunk readable.

Reading: the summary section alone answers counts, times, topics and definitions (cheap on any
size of file); messages come through the chunk indexes in log-time order. A file without a
summary (a killed recorder) is scanned record by record up to its first broken record.
"""

from __future__ import annotations

import contextlib
import os
import struct
from collections.abc import Callable, Iterable, Iterator
from typing import IO, TYPE_CHECKING, BinaryIO

from ros2lite.bag.errors import BagError, MetadataError
from ros2lite.bag.metadata import (
    BagMetadata,
    TopicMetadata,
    dump_metadata,
    dump_qos_list,
    parse_metadata,
    parse_qos_list,
)
from ros2lite.bag.storage import FileSummary, StorageReader, StorageWriter

if TYPE_CHECKING:
    from mcap.records import Channel, McapRecord, Metadata, Schema
    from mcap.records import Message as McapMessage
    from mcap.summary import Summary

__all__ = [
    "COMPRESSIONS",
    "DEFAULT_CHUNK_SIZE",
    "McapStorageReader",
    "McapStorageWriter",
    "open_reader",
    "recover",
]

# rosbag2's chunk size (mcap C++ 1.4 default); rosbag2_storage_mcap presets change it
DEFAULT_CHUNK_SIZE = 768 * 1024
COMPRESSIONS = ("none", "zstd", "lz4")
# storage preset profiles of rosbag2_storage_mcap: compression and chunk size
PRESETS: dict[str, tuple[str, int]] = {
    "none": ("none", DEFAULT_CHUNK_SIZE),
    "fastwrite": ("none", DEFAULT_CHUNK_SIZE),
    "zstd_fast": ("zstd", DEFAULT_CHUNK_SIZE),
    "zstd_small": ("zstd", 4 * 1024 * 1024),
}


def _library() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return f"ros2lite {version('ros2lite')}"
    except PackageNotFoundError:  # pragma: no cover - running from a source tree
        return "ros2lite"


class _DirectFile:
    """A write-only file with no user-space buffer and a known position. The mcap writer
    assembles whole chunks in memory and hands each over in one write, so buffering again
    would only delay data on its way to the OS."""

    def __init__(self, path: str) -> None:
        self.path = path
        from ros2lite.util.files import create_new

        self._fd = create_new(path)
        self._pos = 0

    def write(self, data: bytes | bytearray | memoryview) -> int:
        view = memoryview(data).cast("B")
        n = len(view)
        done = 0
        while done < n:
            done += os.write(self._fd, view[done:])
        self._pos += n
        return n

    def tell(self) -> int:
        return self._pos

    def flush(self) -> None:
        pass

    def close(self) -> None:
        if self._fd >= 0:
            fd, self._fd = self._fd, -1
            os.close(fd)


def _os_error(path: str, e: OSError) -> BagError:
    return BagError(f"Cannot write '{path}': {e.strerror or e}")


class McapStorageWriter:
    """One `.mcap` file of a bag."""

    def __init__(
        self, path: str, *, compression: str = "none", chunk_size: int = DEFAULT_CHUNK_SIZE
    ) -> None:
        from mcap.writer import CompressionType, IndexType, Writer

        if compression not in COMPRESSIONS:
            raise BagError(
                f"Unknown MCAP compression '{compression}' (choose from {', '.join(COMPRESSIONS)})"
            )
        self.path = path
        try:
            self._file = _DirectFile(path)
        except OSError as e:
            raise _os_error(path, e) from None
        self._writer = Writer(
            self._file,  # type: ignore[arg-type]  # a file-like object is all it needs
            chunk_size=chunk_size,
            compression={
                "none": CompressionType.NONE,
                "zstd": CompressionType.ZSTD,
                "lz4": CompressionType.LZ4,
            }[compression],
            index_types=IndexType.ALL,
            use_chunking=True,
            use_statistics=True,
            use_summary_offsets=True,
            repeat_channels=True,
            repeat_schemas=True,
        )
        self._schemas: dict[str, int] = {}
        self._closed = False
        try:
            self._writer.start(profile="ros2", library=_library())
        except OSError as e:
            self.abandon()
            raise _os_error(path, e) from None
        # the hot path: mcap's own method, bound once
        self.add_message = self._writer.add_message

    @property
    def size(self) -> int:
        """Bytes handed to the OS so far (the chunk being built is not counted)."""
        return self._file.tell()

    def add_schema(self, type_name: str, encoding: str, text: str) -> int:
        """Register a type's definition once; its schema id."""
        sid = self._schemas.get(type_name)
        if sid is None:
            sid = self._schemas[type_name] = self._writer.register_schema(
                type_name, encoding, text.encode()
            )
        return sid

    def add_channel(self, topic: TopicMetadata, schema_id: int) -> int:
        """Register a topic with its QoS and type hash; its channel id."""
        cid: int = self._writer.register_channel(
            topic.name,
            topic.serialization_format,
            schema_id,
            {
                "offered_qos_profiles": dump_qos_list(topic.offered_qos_profiles),
                "topic_type_hash": topic.type_description_hash,
            },
        )
        return cid

    def add_rosbag2_metadata(self, metadata: BagMetadata) -> None:
        """Store the bag's metadata as known now in a `rosbag2` record."""
        self._writer.add_metadata(
            "rosbag2", {"serialized_metadata": dump_metadata(metadata, top_key=False)}
        )

    def flush_chunk(self) -> None:
        """Close the chunk in progress so its messages reach the file now."""
        self._writer.flush()

    def close(self, metadata: BagMetadata | None = None) -> None:
        """Write the last chunk, the summary and the footer; the file is complete after this."""
        if self._closed:
            return
        self._closed = True
        try:
            if metadata is not None:
                self.add_rosbag2_metadata(metadata)
            self._writer.finish()
        except OSError as e:
            raise _os_error(self.path, e) from None
        finally:
            self._file.close()

    def abandon(self) -> None:
        """Stop without finishing (the disk refused us): what is on disk stays recoverable."""
        self._closed = True
        self._file.close()


# -- reading -------------------------------------------------------------------------------------


def _topic(channel: Channel, schema: Schema | None) -> TopicMetadata:
    meta = channel.metadata or {}
    try:
        qos = parse_qos_list(meta.get("offered_qos_profiles"))
    except MetadataError:
        qos = []
    return TopicMetadata(
        name=channel.topic,
        type=schema.name if schema is not None else "",
        serialization_format=channel.message_encoding,
        offered_qos_profiles=qos,
        type_description_hash=meta.get("topic_type_hash", "") or "",
    )


def _rosbag2_record(record: Metadata) -> tuple[BagMetadata | None, str]:
    data = record.metadata
    text = data.get("serialized_metadata")
    if text:
        with contextlib.suppress(MetadataError):
            m = parse_metadata(text, top_key=False)
            return m, m.ros_distro
    return None, data.get("ROS_DISTRO", "")


def _note_rosbag2_records(summary: FileSummary, records: Iterable[Metadata]) -> None:
    """Put into `summary` the bag metadata and ROS distro of the last `rosbag2` records
    that carry them."""
    for record in records:
        if record.name == "rosbag2":
            m, d = _rosbag2_record(record)
            summary.metadata, summary.ros_distro = m or summary.metadata, d or summary.ros_distro


def _note_channel(
    topics: dict[str, TopicMetadata],
    definitions: dict[str, tuple[str, str]],
    channel: Channel,
    schema: Schema | None,
) -> TopicMetadata:
    """A channel's topic (the first channel of a name stands for it) and its schema's text."""
    t = _topic(channel, schema)
    topics.setdefault(t.name, t)
    if schema is not None and schema.name not in definitions:
        definitions[schema.name] = (schema.encoding, _text(schema.data))
    return t


class McapStorageReader:
    """One `.mcap` file, read through its summary when it has one."""

    def __init__(self, path: str) -> None:
        from mcap.reader import SeekingReader

        self.path = path
        try:
            self._stream = open(path, "rb")  # noqa: SIM115 - closed by close()
        except OSError as e:
            raise BagError(f"Cannot open '{path}': {e.strerror or e}") from None
        try:
            self._reader = SeekingReader(self._stream)
            self._reader.get_header()
        except Exception as e:
            self._stream.close()
            raise BagError(f"'{path}' is not an MCAP file ({e or type(e).__name__})") from None
        self._summary: Summary | None = None
        self._indexed: bool | None = None

    def close(self) -> None:
        """Close the file."""
        self._stream.close()

    def _mcap_summary(self) -> Summary | None:
        """mcap's Summary, or None for a file that has none (or a broken end)."""
        if self._indexed is None:
            try:
                self._summary = self._reader.get_summary()
            except Exception:
                self._summary = None
            self._indexed = self._summary is not None and self._summary.statistics is not None
        return self._summary if self._indexed else None

    def summary(self) -> FileSummary:
        """From the summary section; a file without one is scanned."""
        s = self._mcap_summary()
        stats = s.statistics if s is not None else None
        if s is None or stats is None:  # (a summary counts only with its statistics)
            return self._scan_summary()
        by_channel: dict[int, TopicMetadata] = {}
        topics: dict[str, TopicMetadata] = {}
        definitions: dict[str, tuple[str, str]] = {}
        for cid, channel in s.channels.items():
            schema = s.schemas.get(channel.schema_id)
            by_channel[cid] = _note_channel(topics, definitions, channel, schema)
        summary = FileSummary(
            list(topics.values()), dict.fromkeys(topics, 0), definitions=definitions
        )
        for cid, n in stats.channel_message_counts.items():
            if cid in by_channel:
                summary.counts[by_channel[cid].name] += n
        if stats.message_count:
            summary.message_count = stats.message_count
            summary.start, summary.end = stats.message_start_time, stats.message_end_time
        _note_rosbag2_records(summary, self._metadata_records())
        return summary

    def _metadata_records(self) -> Iterator[Metadata]:
        s = self._summary
        if s is None or not s.metadata_indexes:
            return iter(())
        return (r for r in self._reader.iter_metadata() if r.name == "rosbag2")

    def messages(
        self, topics: set[str] | None = None, start: int | None = None, stop: int | None = None
    ) -> Iterator[tuple[str, bytes, int, int]]:
        """(topic, data, log_time, publish_time) in log-time order, `start <= t < stop`."""
        if self._mcap_summary() is None:
            # a stream of its own: a summary scan while this generator is paused must not
            # move its position
            with open(self.path, "rb") as stream:
                for _schemas, channel, m in _scan(stream):
                    if (
                        (topics is None or channel.topic in topics)
                        and (start is None or m.log_time >= start)
                        and (stop is None or m.log_time < stop)
                    ):
                        yield channel.topic, m.data, m.log_time, m.publish_time
            return
        yield from self._indexed_messages(topics, start, stop)

    def _indexed_messages(
        self, topics: set[str] | None, start: int | None, stop: int | None
    ) -> Iterator[tuple[str, bytes, int, int]]:
        """Messages through the chunk indexes, in log-time order, each chunk's CRC checked:
        a corrupt chunk is reported (file, offset) and skipped, the others are still read.
        A message whose time lies outside its chunk's indexed range (a flipped byte in a
        chunk without CRC) is refused the same way."""
        import heapq

        from mcap.records import Message

        summary = self._summary
        assert summary is not None  # only indexed files are read this way
        channels = summary.channels
        wanted = {cid for cid, c in channels.items() if topics is None or c.topic in topics}
        chunks = sorted(
            (
                c
                for c in summary.chunk_indexes
                if (stop is None or c.message_start_time < stop)
                and (start is None or c.message_end_time >= start)
                and (not c.message_index_offsets or wanted & set(c.message_index_offsets))
            ),
            key=lambda c: (c.message_start_time, c.chunk_start_offset),
        )
        pending: list[tuple[int, int, int, str, bytes, int]] = []
        for i, index in enumerate(chunks):
            where = index.chunk_start_offset
            records: list[McapRecord] = []
            problem = self._read_chunk(where, records)
            if problem is not None:
                kept = sum(isinstance(r, Message) for r in records)
                _warn(
                    f"'{self.path}': the chunk at byte {where} {problem}: {kept} of its "
                    "messages kept, the rest dropped; the other chunks are read"
                )
            lo, hi = index.message_start_time, index.message_end_time
            refused = 0
            for pos, record in enumerate(records):
                if not isinstance(record, Message) or record.channel_id not in wanted:
                    continue
                t = record.log_time
                if not lo <= t <= hi:
                    refused += 1
                    continue
                if (start is not None and t < start) or (stop is not None and t >= stop):
                    continue
                heapq.heappush(
                    pending,
                    (
                        t,
                        i,
                        pos,
                        channels[record.channel_id].topic,
                        record.data,
                        record.publish_time,
                    ),
                )
            if refused:
                _warn(
                    f"'{self.path}': {refused} message(s) in the chunk at offset {where} have "
                    "log times outside the chunk's own range (corrupt); skipped"
                )
            horizon = chunks[i + 1].message_start_time if i + 1 < len(chunks) else None
            while pending and (horizon is None or pending[0][0] <= horizon):
                t, _, _, topic, data, publish_time = heapq.heappop(pending)
                yield topic, data, t, publish_time

    def _read_chunk(self, where: int, kept: list[McapRecord]) -> str | None:
        """The trusted records of the chunk at `where` into `kept`; what was wrong, if aught."""
        stream = self._stream
        size = stream.seek(0, os.SEEK_END)
        stream.seek(where)
        op_length = stream.read(9)
        if len(op_length) < 9 or op_length[0] != _CHUNK:
            return "is not where the index says"
        (length,) = struct.unpack_from("<Q", op_length, 1)
        try:
            head = _ChunkHead(stream.read(min(length, 40 + 64)))
        except _Damage as e:
            return str(e)
        start = where + 9 + 32 + len(head.compression.encode()) + 8
        end = where + 9 + length
        stream.seek(start)
        data = stream.read(max(0, min(head.records_length, end - start, size - start)))
        whole = end <= size and start + head.records_length <= end
        problem = _chunk_records(head, data, whole, kept)
        return problem if whole else problem or "is cut short"

    def _scan_summary(self) -> FileSummary:
        """Summary of a file without one, from its records up to the first broken one."""
        topics: dict[str, TopicMetadata] = {}
        summary = FileSummary([], {}, complete=False)
        records: list[Metadata] = []

        def on_channel(channel: Channel, schema: Schema | None) -> None:
            t = _note_channel(topics, summary.definitions, channel, schema)
            summary.counts.setdefault(t.name, 0)

        for _schemas, channel, m in _scan(
            self._stream,
            on_metadata=records.append,
            on_channel=on_channel,
            problems=summary.problems,
        ):
            summary.add(channel.topic, 1, m.log_time, m.log_time)
        summary.topics = list(topics.values())
        _note_rosbag2_records(summary, records)
        return summary


def _warn(message: str) -> None:
    """A problem found while reading (a corrupt chunk): said once, reading goes on."""
    from ros2lite.logging import get_logger

    get_logger("rosbag2_storage").warn(message)


def _text(data: bytes) -> str:
    return data.decode("utf-8", errors="replace")


# -- reading record by record: what a damaged file still holds -----------------------------------

_MAGIC = b"\x89MCAP0\r\n"
_PIECE = 1 << 20  # decompressed bytes taken at a time: memory stays bounded whatever a chunk says
(_FOOTER, _SCHEMA, _CHANNEL, _MESSAGE, _CHUNK, _METADATA) = (2, 3, 4, 5, 6, 12)
_KNOWN_OPCODES = range(1, 16)  # MCAP's records; 0x80 and up are private ones (skipped)
_IN_CHUNK = (_SCHEMA, _CHANNEL, _MESSAGE)


class _Damage(Exception):
    """Where reading had to stop and why (said in the report line)."""


def _crc_table() -> tuple[list[int], dict[int, int]]:
    """zlib's CRC-32 table, and its entries' top bytes back to their index (the table is
    built so that they are all different, which makes a step of the CRC undoable)."""
    table = []
    for i in range(256):
        c = i
        for _ in range(8):
            c = (c >> 1) ^ 0xEDB88320 if c & 1 else c >> 1
        table.append(c)
    return table, {c >> 24: i for i, c in enumerate(table)}


def first_damaged_byte(data: bytes | bytearray, expected: int) -> int | None:
    """The earliest offset at which one changed byte explains `data`'s CRC-32 not being
    `expected`, or None when no single byte does (more damage than that).

    The CRC is linear: the difference of two CRCs of equal length is the CRC of the error
    alone, and a one-byte error `e` followed by `m` zero bytes has the CRC `T[e]` pushed
    through `m` zero steps. Undoing one zero step at a time from the difference finds every
    `m` that fits; the largest is the earliest offset. Every byte before it is as written
    (when the damage is one byte), so the records wholly before it can be kept."""
    import zlib

    table, back = _crc_table()
    single = {c: e for e, c in enumerate(table) if e}
    s = zlib.crc32(data) ^ expected
    n = len(data)
    found = None
    for m in range(n):
        if s in single:
            found = n - 1 - m
        i = back[s >> 24]
        s = (((s ^ table[i]) << 8) | i) & 0xFFFFFFFF
    return found


def _inflate(compression: str, data: bytes, limit: int) -> Iterator[bytes]:
    """A chunk's records in pieces of at most `_PIECE` bytes, never more than `limit` (its
    declared uncompressed size) in all: a chunk that inflates past what it declared raises
    `_Damage` there (a zip bomb costs one piece of memory, not what it inflates to). Input
    cut short yields what it holds."""
    if compression == "":
        if len(data) > limit:
            raise _Damage(f"holds {len(data)} bytes but declares {limit}")
        for i in range(0, len(data), _PIECE):
            yield data[i : i + _PIECE]
        return
    total = 0
    try:
        if compression == "zstd":
            import io

            import zstandard

            with zstandard.ZstdDecompressor().stream_reader(io.BytesIO(data)) as src:
                while piece := src.read(_PIECE):
                    total += len(piece)
                    if total > limit:
                        yield piece[: len(piece) - (total - limit)]
                        raise _Damage(f"inflates past its declared {limit} bytes")
                    yield piece
        elif compression == "lz4":
            import lz4.frame

            lz4_src = lz4.frame.LZ4FrameDecompressor()
            piece = lz4_src.decompress(data, max_length=_PIECE)
            while piece:
                total += len(piece)
                if total > limit:
                    yield piece[: len(piece) - (total - limit)]
                    raise _Damage(f"inflates past its declared {limit} bytes")
                yield piece
                if lz4_src.eof or lz4_src.needs_input:
                    break
                piece = lz4_src.decompress(b"", max_length=_PIECE)
        else:
            raise _Damage(f"has an unknown compression '{compression[:40]}'")
    except _Damage:
        raise
    except Exception as e:  # the decompressor's own complaint about its input
        raise _Damage(f"does not decompress ({e or type(e).__name__})") from None


def _parse(op: int, body: bytes) -> McapRecord | None:
    """One record from its whole body; None when the body does not hold what the record
    says (the first bad record)."""
    import io

    from mcap.data_stream import ReadDataStream
    from mcap.records import Channel, Message, Metadata, Schema

    if op == _MESSAGE:
        if len(body) < 22:
            return None
        cid, seq, log_time, publish_time = struct.unpack_from("<HIQQ", body)
        return Message(cid, log_time, body[22:], publish_time, seq)
    stream = ReadDataStream(io.BytesIO(body))
    kinds: dict[int, Callable[[ReadDataStream], McapRecord]] = {
        _SCHEMA: Schema.read,
        _CHANNEL: Channel.read,
        _METADATA: Metadata.read,
    }
    try:
        record = kinds[op](stream)
    except Exception:
        return None
    return record if stream.count == len(body) else None


class _ChunkHead:
    """A chunk record's fields before its records."""

    __slots__ = ("compression", "crc", "end", "records_length", "size", "start")

    def __init__(self, body: bytes) -> None:
        if len(body) < 40:
            raise _Damage("has a cut header")
        self.start, self.end, self.size, self.crc, n = struct.unpack_from("<QQQII", body)
        if n > 64 or len(body) < 32 + n + 8:
            raise _Damage("has a bad header")
        self.compression = body[32 : 32 + n].decode("ascii", errors="replace")
        (self.records_length,) = struct.unpack_from("<Q", body, 32 + n)


def _chunk_records(
    head: _ChunkHead, data: bytes, whole: bool, kept: list[McapRecord]
) -> str | None:
    """Put into `kept` the records of one chunk that can be trusted: all of them when its
    CRC holds; else those before the first bad record (cut short, inflating past its size,
    a length running out of the chunk, a body that does not parse) or before the byte that
    broke its CRC. Returns what was wrong, or None."""
    if head.size > (1 << 40):
        return f"declares an impossible size ({head.size} bytes)"
    good_until = head.size
    problem = None
    if whole and head.crc:
        import zlib

        try:
            if head.compression == "":
                crc = zlib.crc32(data)
            else:
                crc = 0
                for piece in _inflate(head.compression, data, head.size):
                    crc = zlib.crc32(piece, crc)
        except _Damage as e:
            return str(e)
        if crc != head.crc:
            where = first_damaged_byte(data, head.crc) if head.compression == "" else None
            if where is None:
                return "fails its CRC check"
            good_until = where
            problem = f"fails its CRC check (byte {where} of its records damaged)"
    buf = b""
    done = 0  # bytes of the records parsed so far
    try:
        for piece in _inflate(head.compression, data, head.size):
            buf += piece
            pos = 0
            while len(buf) - pos >= 9:
                op, length = struct.unpack_from("<BQ", buf, pos)
                if op not in _IN_CHUNK and op < 0x80:
                    return problem or f"holds a record of unknown kind ({op})"
                end = done + pos + 9 + length
                if end > head.size:
                    return problem or "holds a record running past its end"
                if end > good_until:
                    return problem
                if len(buf) - pos - 9 < length:
                    break
                if op in _IN_CHUNK:
                    record = _parse(op, buf[pos + 9 : pos + 9 + length])
                    if record is None:
                        return problem or "holds a record that does not parse"
                    kept.append(record)
                pos += 9 + length
            buf = buf[pos:]
            done += pos
    except _Damage as e:
        return problem or str(e)
    if buf or (whole and done != head.size):
        return problem or ("is cut short" if not whole else "ends inside a record")
    return problem


class _Scan:
    """A file read record by record in file order, as `mcap recover` reads it: every record
    that can be trusted up to the first that cannot. A chunk with bad records keeps those
    before them; a chunk cut short keeps its complete records; reading goes on after a
    damaged chunk whose length is still sound. `problems` says what was lost, one line each."""

    def __init__(self, stream: IO[bytes], path: str) -> None:
        self.stream = stream
        self.path = path
        self.problems: list[str] = []
        self.messages = 0
        self.schemas: dict[int, Schema] = {}
        self.channels: dict[int, Channel] = {}

    def records(self) -> Iterator[McapRecord]:
        """Schema, Channel, Message and Metadata records; a message only on a known channel."""
        from mcap.records import Channel, Message, Schema

        for record in self._records():
            if isinstance(record, Message):
                if record.channel_id not in self.channels:
                    continue
                self.messages += 1
            elif isinstance(record, Schema):
                self.schemas[record.id] = record
            elif isinstance(record, Channel):
                self.channels[record.id] = record
            yield record

    def _stop(self, at: int, what: str) -> None:
        self.problems.append(
            f"'{self.path}' is truncated at byte {at} {what}: {self.messages} messages recovered"
        )

    def _records(self) -> Iterator[McapRecord]:
        stream = self.stream
        size = stream.seek(0, os.SEEK_END)
        stream.seek(0)
        if stream.read(8) != _MAGIC:
            self._stop(0, "before its start (not an MCAP file)")
            return
        pos = 8
        while True:
            stream.seek(pos)
            head = stream.read(9)
            if len(head) < 9:
                if head:
                    self._stop(pos, "inside a record")
                else:
                    self._stop(pos, "after a complete record (no summary)")
                return
            op, length = struct.unpack("<BQ", head)
            if op == _FOOTER:
                return
            if op not in _KNOWN_OPCODES and op < 0x80:
                self._stop(pos, f"at a record of unknown kind ({op}); the rest is unreadable")
                return
            whole = length <= size - pos - 9
            if op == _CHUNK:
                yield from self._chunk(pos, length, whole, size)
                if not whole:
                    return
            elif not whole:
                self._stop(pos + 9, "inside a record")
                return
            elif op in (_SCHEMA, _CHANNEL, _MESSAGE, _METADATA):
                record = _parse(op, stream.read(length))
                if record is None:
                    self._stop(pos, "at a record that does not parse; the rest is unreadable")
                    return
                yield record
            pos += 9 + length

    def _chunk(self, pos: int, length: int, whole: bool, size: int) -> Iterator[McapRecord]:
        stream = self.stream
        fixed = stream.read(min(length, 40 + 64))
        try:
            head = _ChunkHead(fixed)
        except _Damage as e:
            if whole:
                self.problems.append(f"'{self.path}': the chunk at byte {pos} {e}; skipped")
            else:
                self._stop(size, "inside a chunk")
            return
        start = pos + 9 + 32 + len(head.compression.encode()) + 8
        stream.seek(start)
        inner_whole = whole and head.records_length <= length - (start - pos - 9)
        data = stream.read(min(head.records_length, max(0, pos + 9 + length - start)))
        kept: list[McapRecord] = []
        problem = _chunk_records(head, data, inner_whole, kept)
        before = self.messages
        yield from kept
        if not whole:
            self._stop(size, "inside a chunk")
        elif not inner_whole:
            self.problems.append(
                f"'{self.path}': the chunk at byte {pos} has a bad length: "
                f"{self.messages - before} of its messages kept, the rest dropped"
            )
        elif problem is not None:
            self.problems.append(
                f"'{self.path}': the chunk at byte {pos} {problem}: "
                f"{self.messages - before} of its messages kept, the rest dropped"
            )


def _scan(
    stream: IO[bytes],
    on_metadata: Callable[[Metadata], object] | None = None,
    on_channel: Callable[[Channel, Schema | None], object] | None = None,
    problems: list[str] | None = None,
) -> Iterator[tuple[dict[int, Schema], Channel, McapMessage]]:
    """Every message record in file order that can be trusted, up to the first that cannot
    (see `_Scan`); what was lost goes into `problems` when the scan ends."""
    from mcap.records import Channel, Message, Metadata

    scan = _Scan(stream, getattr(stream, "name", "the file"))
    seen: set[int] = set()
    try:
        for record in scan.records():
            if isinstance(record, Message):
                yield scan.schemas, scan.channels[record.channel_id], record
            elif isinstance(record, Channel):
                if on_channel is not None and record.id not in seen:
                    on_channel(record, scan.schemas.get(record.schema_id))
                seen.add(record.id)
            elif isinstance(record, Metadata) and on_metadata is not None:
                on_metadata(record)
    finally:
        if problems is not None:
            problems.extend(scan.problems)


def open_reader(path: str) -> StorageReader:
    """The plugin's reader of one file."""
    return McapStorageReader(path)


def open_writer(
    path: str, *, compression: str = "none", chunk_size: int = DEFAULT_CHUNK_SIZE
) -> StorageWriter:
    """The plugin's writer of one new file."""
    return McapStorageWriter(path, compression=compression, chunk_size=chunk_size)


def recover(path: str) -> tuple[int, list[str]]:
    """Rewrite a file that has no summary (its recorder was killed, a copy cut short) into a
    complete MCAP holding every record that can be trusted (see `_Scan`); returns the
    messages kept and what was lost, one line each.

    The new file is written beside the old one and renamed over it, so an interrupted
    recovery leaves the original untouched."""
    from ros2lite.util.files import temp_beside

    fd, tmp = temp_beside(path, ".recovering")  # a fresh name: no planted file is written
    try:
        os.fchmod(fd, 0o644)
        problems: list[str] = []
        kept = _copy_readable(path, os.fdopen(fd, "wb"), problems)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    os.replace(tmp, path)
    return kept, problems


def _copy_readable(path: str, dst: BinaryIO, problems: list[str]) -> int:
    """Copy every readable message of `path` into a complete MCAP written to `dst`."""
    from mcap.writer import CompressionType, IndexType, Writer

    with open(path, "rb") as src, dst:
        writer = Writer(
            dst,
            chunk_size=DEFAULT_CHUNK_SIZE,
            compression=CompressionType.NONE,
            index_types=IndexType.ALL,
        )
        writer.start(profile="ros2", library=_library())
        schema_ids: dict[int, int] = {}
        channel_ids: dict[int, int] = {}
        metadata: list[Metadata] = []
        kept = 0
        for schemas, channel, m in _scan(src, on_metadata=metadata.append, problems=problems):
            cid = channel_ids.get(channel.id)
            if cid is None:
                sid = 0
                schema = schemas.get(channel.schema_id)
                if schema is not None:
                    sid = schema_ids.get(schema.id, 0)
                    if not sid:
                        sid = schema_ids[schema.id] = writer.register_schema(
                            schema.name, schema.encoding, schema.data
                        )
                cid = channel_ids[channel.id] = writer.register_channel(
                    channel.topic, channel.message_encoding, sid, dict(channel.metadata)
                )
            writer.add_message(cid, m.log_time, m.data, m.publish_time, m.sequence)
            kept += 1
        for record in metadata:
            writer.add_metadata(record.name, dict(record.metadata))
        writer.finish()
    return kept


def is_complete(path: str) -> bool:
    """Whether a file has its summary (was closed properly)."""
    reader = McapStorageReader(path)
    try:
        return reader._mcap_summary() is not None
    finally:
        reader.close()
