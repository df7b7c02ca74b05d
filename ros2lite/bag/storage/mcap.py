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

        from mcap.data_stream import ReadDataStream
        from mcap.records import Chunk, Message
        from mcap.stream_reader import breakup_chunk

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
            try:
                self._stream.seek(where + 1 + 8)
                records = breakup_chunk(Chunk.read(ReadDataStream(self._stream)), validate_crc=True)
            except Exception as e:  # CRC mismatch, bad compression, cut short: skip it
                _warn(
                    f"'{self.path}': corrupt chunk at offset {where} skipped "
                    f"({e or type(e).__name__}); the other chunks are read"
                )
                continue
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

    def _scan_summary(self) -> FileSummary:
        """Summary of a file without one, from its records up to the first broken one."""
        topics: dict[str, TopicMetadata] = {}
        summary = FileSummary([], {}, complete=False)
        records: list[Metadata] = []

        def on_channel(channel: Channel, schema: Schema | None) -> None:
            t = _note_channel(topics, summary.definitions, channel, schema)
            summary.counts.setdefault(t.name, 0)

        for _schemas, channel, m in _scan(
            self._stream, on_metadata=records.append, on_channel=on_channel
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


def _scan(
    stream: IO[bytes],
    on_metadata: Callable[[Metadata], object] | None = None,
    on_channel: Callable[[Channel, Schema | None], object] | None = None,
) -> Iterator[tuple[dict[int, Schema], Channel, McapMessage]]:
    """Every message record in file order, stopping quietly at the first record that cannot
    be read (a truncated chunk at the end of a killed recording)."""
    from mcap.records import Channel, Chunk, Message, Metadata, Schema
    from mcap.stream_reader import StreamReader, breakup_chunk

    stream.seek(0)
    schemas: dict[int, Schema] = {}
    channels: dict[int, Channel] = {}
    records = StreamReader(stream, skip_magic=False, emit_chunks=True).records
    queue: list[McapRecord] = []
    while True:
        if queue:
            record = queue.pop()
        else:
            try:
                record = next(records)
            except StopIteration:
                return
            except Exception:
                return  # truncated or corrupt from here on
        if isinstance(record, Chunk):
            try:
                queue = breakup_chunk(record, validate_crc=True)[::-1]
            except Exception as e:
                where = getattr(stream, "name", "the file")
                _warn(f"'{where}': a corrupt chunk skipped ({e or type(e).__name__})")
            continue
        if isinstance(record, Message):
            channel = channels.get(record.channel_id)
            if channel is not None:
                yield schemas, channel, record
        elif isinstance(record, Schema):
            schemas[record.id] = record
        elif isinstance(record, Channel):
            if record.id not in channels and on_channel is not None:
                on_channel(record, schemas.get(record.schema_id))
            channels[record.id] = record
        elif isinstance(record, Metadata) and on_metadata is not None:
            on_metadata(record)


def open_reader(path: str) -> StorageReader:
    """The plugin's reader of one file."""
    return McapStorageReader(path)


def open_writer(
    path: str, *, compression: str = "none", chunk_size: int = DEFAULT_CHUNK_SIZE
) -> StorageWriter:
    """The plugin's writer of one new file."""
    return McapStorageWriter(path, compression=compression, chunk_size=chunk_size)


def recover(path: str) -> int:
    """Rewrite a file that has no summary (its recorder was killed) into a complete MCAP
    holding every message up to its last complete chunk; returns the messages kept.

    The new file is written beside the old one and renamed over it, so an interrupted
    recovery leaves the original untouched."""
    from ros2lite.util.files import temp_beside

    fd, tmp = temp_beside(path, ".recovering")  # a fresh name: no planted file is written
    try:
        os.fchmod(fd, 0o644)
        kept = _copy_readable(path, os.fdopen(fd, "wb"))
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    os.replace(tmp, path)
    return kept


def _copy_readable(path: str, dst: BinaryIO) -> int:
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
        for schemas, channel, m in _scan(src, on_metadata=metadata.append):
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
