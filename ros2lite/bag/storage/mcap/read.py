"""Reading an MCAP file: the summary section alone answers counts, times, topics and
definitions (cheap on any size of file); messages come through the chunk indexes in log-time
order. A file without a summary (a killed recorder) is scanned record by record up to its first
broken record (`scan`).
"""

from __future__ import annotations

import contextlib
import os
import stat
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING

from ros2lite.bag.errors import BagError, MetadataError
from ros2lite.bag.metadata import BagMetadata, TopicMetadata, parse_metadata, parse_qos_list
from ros2lite.bag.storage import FileSummary
from ros2lite.bag.storage.mcap.scan import _scan, read_chunk_at

if TYPE_CHECKING:
    from mcap.data_stream import ReadDataStream
    from mcap.records import Channel, ChunkIndex, McapRecord, Metadata, Schema
    from mcap.summary import Summary


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
            # a FIFO named by a hostile metadata.yaml would block open() until a writer came
            # (R5-B7): only a regular file is opened
            fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
        except OSError as e:
            raise BagError(f"Cannot open '{path}': {e.strerror or e}") from None
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            os.close(fd)
            raise BagError(f"Cannot open '{path}': not a regular file")
        if info.st_size == 0:
            os.close(fd)
            raise BagError(f"'{path}' is empty (0 bytes): not an MCAP file")
        os.set_blocking(fd, True)
        self._stream = os.fdopen(fd, "rb")
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

    @property
    def indexed(self) -> bool:
        """Whether the file ends in a summary with statistics (its writer closed it), so
        that counts and messages come through the indexes, not a scan."""
        return self._mcap_summary() is not None

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
        _note_rosbag2_records(summary, self._metadata_records(summary.problems))
        return summary

    def _metadata_records(self, problems: list[str] | None = None) -> Iterator[Metadata]:
        """The `rosbag2` metadata records; one that does not decode (a flipped byte, R5-B6)
        is named in `problems` and passed over: the messages do not depend on it."""
        s = self._summary
        if s is None or not s.metadata_indexes:
            return
        from mcap.records import Metadata

        stream = self._stream
        for index in s.metadata_indexes:
            if index.name != "rosbag2":
                continue
            try:
                stream.seek(index.offset + 9)
                body = stream.read(max(0, min(index.length - 9, 1 << 26)))
                record = Metadata.read(_stream_of(body))
            except Exception as e:
                if problems is not None:
                    problems.append(
                        f"'{self.path}': its rosbag2 metadata record at byte {index.offset} is "
                        f"damaged ({type(e).__name__}); read without it"
                    )
                continue
            yield record

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
                for c in self._chunk_indexes(summary.chunk_indexes)
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

    def _chunk_indexes(self, indexes: Iterable[ChunkIndex]) -> list[ChunkIndex]:
        """Each chunk once, however many indexes name it (R5-B3: one chunk behind 10,000
        indexes was read 10,000 times, every message repeated), and no index whose chunk
        overlaps another's; what was dropped is said in one line."""
        listed = list(indexes)
        by_offset: dict[int, ChunkIndex] = {}
        for index in listed:
            by_offset.setdefault(index.chunk_start_offset, index)
        repeated = len(listed) - len(by_offset)
        kept: list[ChunkIndex] = []
        overlapping = 0
        end = -1
        for offset in sorted(by_offset):
            index = by_offset[offset]
            if offset < end:
                overlapping += 1
                continue
            kept.append(index)
            end = offset + max(index.chunk_length, 1)
        if repeated or overlapping:
            _warn(
                f"'{self.path}': its summary names {repeated} chunk(s) more than once and "
                f"{overlapping} overlapping another; each chunk is read once"
            )
        return kept

    def _read_chunk(self, where: int, kept: list[McapRecord]) -> str | None:
        """The trusted records of the chunk at `where` into `kept`; what was wrong, if aught."""
        return read_chunk_at(self._stream, where, kept)

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
            headers_only=True,
            path=self.path,
        ):
            summary.add(channel.topic, 1, m.log_time, m.log_time)
        summary.topics = list(topics.values())
        _note_rosbag2_records(summary, records)
        return summary


def _warn(message: str) -> None:
    """A problem found while reading (a corrupt chunk): said once, reading goes on."""
    from ros2lite.logging import get_logger

    get_logger("rosbag2_storage").warn(message)


def _stream_of(body: bytes) -> ReadDataStream:
    import io

    from mcap.data_stream import ReadDataStream

    return ReadDataStream(io.BytesIO(body))


def _text(data: bytes) -> str:
    return data.decode("utf-8", errors="replace")
