"""Writing a bag: the rosbag2 directory layout over the mcap storage plugin.

`Writer` owns the directory, the split files (`<name>_0.mcap`, `_1`, …), the per-topic and
per-file counts and metadata.yaml. Topics are created once with their type, QoS and type hash;
messages go in as CDR bytes (or message objects, serialized here) with their receive time.
The recorder uses the same class from its writer thread, so its hot path (`write_raw`) stays a
handful of attribute look-ups per message.
"""

from __future__ import annotations

import contextlib
import os
import time
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from ros2lite.bag.errors import BagError
from ros2lite.bag.metadata import (
    EMPTY_STARTING_TIME,
    METADATA_FILENAME,
    BagMetadata,
    FileInformation,
    TopicInformation,
    TopicMetadata,
    write_metadata_file,
)
from ros2lite.bag.reader import metadata_from_files
from ros2lite.bag.storage import StorageWriter
from ros2lite.bag.storage.mcap import DEFAULT_CHUNK_SIZE, PRESETS, McapStorageReader, open_writer
from ros2lite.qos import QoSProfile

if TYPE_CHECKING:
    from ros2lite.type_support import Msg

__all__ = ["MIN_SPLIT_SIZE", "Writer", "type_definition"]

# rosbag2's smallest --max-bag-size (get_minimum_split_file_size of the mcap plugin)
MIN_SPLIT_SIZE = 1024
# what a message record adds to its payload in an MCAP chunk (opcode, length, header fields)
_RECORD_OVERHEAD = 1 + 8 + 2 + 4 + 8 + 8


def type_definition(type_name: str) -> tuple[str, str, str]:
    """(schema encoding, full ros2msg text, RIHS01 hash) from the local search path, or empty
    values for a type it does not know (rosbag2 writes an empty schema then)."""
    from ros2lite.interfaces import InterfaceError, definition_text, type_hash

    try:
        return "ros2msg", definition_text(type_name), type_hash(type_name)
    except (InterfaceError, LookupError, ValueError, OSError):
        return "", "", ""


@dataclass
class _Topic:
    meta: TopicMetadata
    encoding: str
    definition: str
    channel: int = 0
    count: int = 0


class Writer:
    """A rosbag2 bag being written.

    >>> with Writer('my_bag') as bag:
    ...     bag.write('/chatter', String(data='hi'), time.time_ns())

    `max_bag_size` (bytes) and `max_bag_duration` (seconds) split the bag into more files;
    `compression` ('none', 'zstd', 'lz4') compresses MCAP chunks, which keeps every file
    indexable (rosbag2's storage preset profiles `zstd_fast`/`zstd_small` map here too).
    """

    def __init__(
        self,
        uri: str | os.PathLike[str],
        *,
        storage_id: str = "mcap",
        compression: str = "none",
        chunk_size: int = DEFAULT_CHUNK_SIZE,
        preset: str | None = None,
        max_bag_size: int = 0,
        max_bag_duration: float = 0.0,
        custom_data: dict[str, str] | None = None,
    ) -> None:
        if storage_id != "mcap":
            raise BagError(f"Writing storage '{storage_id}' is not supported (use mcap)")
        if preset is not None:
            if preset not in PRESETS:
                raise BagError(
                    f"Unknown storage preset profile '{preset}' (choose from {', '.join(PRESETS)})"
                )
            compression, chunk_size = PRESETS[preset]
        if max_bag_size and max_bag_size < MIN_SPLIT_SIZE:
            raise BagError(
                f"Invalid bag splitting size given. Please provide a value greater "
                f"than {MIN_SPLIT_SIZE}."
            )
        if max_bag_size < 0 or max_bag_duration < 0:
            raise BagError("Bag split limits must not be negative")
        self.path = Path(uri)
        if not self.path.name:
            raise BagError(f"Invalid bag path '{uri}'")
        self.compression = compression
        self.chunk_size = chunk_size
        self.max_bag_size = max_bag_size
        self.max_bag_duration = int(max_bag_duration * 1e9)
        self.custom_data = dict(custom_data) if custom_data else None
        self._topics: list[_Topic] = []
        self._by_name: dict[str, int] = {}
        self._storage: StorageWriter | None = None
        self._files: list[FileInformation] = []
        self._file: FileInformation | None = None
        self._file_bytes = 0
        self._start = EMPTY_STARTING_TIME
        self._end = 0
        self._count = 0
        self._open = False
        self._closed = False

    # -- lifecycle ------------------------------------------------------------------------------
    def open(self) -> Writer:
        """Create the bag directory and its first file (BagError if it already exists)."""
        if self._open:
            return self
        if self.path.exists():
            raise BagError(f"Output folder '{self.path}' already exists.")
        try:
            self.path.mkdir(parents=True)
        except OSError as e:
            raise BagError(f"Cannot create '{self.path}': {e.strerror or e}") from None
        self._open = True
        try:
            self._next_file()
        except BagError:
            self._remove_if_empty()
            raise
        return self

    def __enter__(self) -> Writer:
        return self.open()

    def __exit__(self, *exc: object) -> None:
        self.close()

    def _remove_if_empty(self) -> None:
        try:
            if self.path.is_dir() and not any(self.path.iterdir()):
                self.path.rmdir()
        except OSError:
            pass

    @property
    def files(self) -> list[str]:
        """The bag's files written so far, relative to its directory."""
        return [f.path for f in self._files]

    @property
    def message_count(self) -> int:
        """Messages written so far."""
        return self._count

    def _next_file(self) -> None:
        name = f"{self.path.name}_{len(self._files)}.mcap"
        storage = open_writer(
            str(self.path / name), compression=self.compression, chunk_size=self.chunk_size
        )
        self._storage = storage
        self._file = FileInformation(path=name)
        self._files.append(self._file)
        self._file_bytes = 0
        for topic in self._topics:
            self._register(topic)
        # rosbag2 puts the metadata known so far in every file when it is opened
        storage.add_rosbag2_metadata(self.metadata())
        self._add = storage.add_message

    def _register(self, topic: _Topic) -> None:
        assert self._storage is not None
        sid = self._storage.add_schema(topic.meta.type, topic.encoding, topic.definition)
        topic.channel = self._storage.add_channel(topic.meta, sid)

    def split(self) -> None:
        """Close the current file and go on in the next one (`<name>_<N+1>.mcap`)."""
        storage = self._require()
        storage.close(self.metadata())
        self._next_file()

    def close(self) -> None:
        """Finish the last file and write metadata.yaml. Idempotent."""
        if self._closed or not self._open:
            return
        self._closed = True
        storage, self._storage = self._storage, None
        if storage is not None:
            try:
                storage.close(self.metadata())
            except BagError:
                storage.abandon()
                self._write_metadata_from_disk()
                raise
        write_metadata_file(self.path, self.metadata())

    def abandon(self) -> None:
        """Give up after a write error: keep what reached the disk and describe exactly
        that in metadata.yaml, if it can still be written."""
        if self._closed:
            return
        self._closed = True
        if self._storage is not None:
            self._storage.abandon()
        self._write_metadata_from_disk()

    def _write_metadata_from_disk(self) -> None:
        # after a failed write the counts in memory include messages that never reached
        # the file, so the metadata is read back from the files themselves

        with contextlib.suppress(Exception):
            summaries = []
            for f in self._files:
                reader = McapStorageReader(str(self.path / f.path))
                try:
                    summaries.append(reader.summary())
                finally:
                    reader.close()
            meta = metadata_from_files([f.path for f in self._files], summaries, "mcap")
            meta.custom_data = self.custom_data
            meta.ros_distro = self.metadata().ros_distro
            write_metadata_file(self.path, meta)

    def discard(self) -> None:
        """Remove the bag again (nothing was recorded: e.g. no graph to record from)."""
        self._closed = True
        if self._storage is not None:
            self._storage.abandon()
        for name in [f.path for f in self._files] + [METADATA_FILENAME]:
            with contextlib.suppress(OSError):
                (self.path / name).unlink()
        self._remove_if_empty()

    def _require(self) -> StorageWriter:
        if not self._open:
            self.open()
        if self._closed or self._storage is None:
            raise BagError("bag writer is closed")
        return self._storage

    # -- topics and messages --------------------------------------------------------------------
    def create_topic(
        self,
        name: str,
        type_name: str,
        *,
        offered_qos_profiles: Iterable[QoSProfile] = (),
        type_description_hash: str | None = None,
        definition: tuple[str, str] | None = None,
        serialization_format: str = "cdr",
    ) -> int:
        """Add a topic; returns its id for `write_raw`. `definition` is (encoding, text);
        by default both it and the hash come from the local type search path."""
        self._require()
        if name in self._by_name:
            return self._by_name[name]
        from ros2lite.interfaces import InterfaceError
        from ros2lite.interfaces.parser import validate_type_name

        try:  # a name from the wire or from another bag is written into this one
            validate_type_name(type_name)
        except InterfaceError as e:
            raise BagError(f"Topic '{name}': {e}") from None
        encoding, text, local_hash = type_definition(type_name)
        if definition is not None:
            encoding, text = definition
        meta = TopicMetadata(
            name=name,
            type=type_name,
            serialization_format=serialization_format,
            offered_qos_profiles=list(offered_qos_profiles),
            type_description_hash=local_hash
            if type_description_hash is None
            else type_description_hash,
        )
        topic = _Topic(meta, encoding, text)
        self._register(topic)
        self._topics.append(topic)
        tid = self._by_name[name] = len(self._topics) - 1
        return tid

    def topic_id(self, name: str) -> int:
        """The id `create_topic` gave a topic."""
        return self._by_name[name]

    def write(
        self,
        topic: str,
        message: Msg | bytes | bytearray | memoryview,
        log_time: int | None = None,
        publish_time: int | None = None,
    ) -> None:
        """Write one message (CDR bytes or a message object) on a topic. A message object on
        a topic not created yet creates it with the message's type."""
        if log_time is None:
            log_time = time.time_ns()
        tid = self._by_name.get(topic)
        if isinstance(message, (bytes, bytearray, memoryview)):
            if tid is None:
                raise BagError(
                    f"Topic '{topic}' was not created (create_topic) and raw bytes "
                    f"do not say their type"
                )
            data = bytes(message)
        else:
            from ros2lite.interfaces import serialize

            type_name = getattr(message, "_TYPE_NAME", None)
            if type_name is None:
                raise TypeError(f"not a ros2lite message: {message!r}")
            if tid is None:
                tid = self.create_topic(topic, type_name)
            elif self._topics[tid].meta.type != type_name:
                raise BagError(
                    f"Topic '{topic}' has type {self._topics[tid].meta.type}, not {type_name}"
                )
            data = serialize(message)
        self.write_raw(tid, data, log_time, log_time if publish_time is None else publish_time)

    def write_raw(self, tid: int, data: bytes, log_time: int, publish_time: int) -> None:
        """The hot path: one message of a created topic, as CDR bytes."""
        if self._storage is None:
            self._require()
        f = self._file
        assert f is not None
        if (
            (self.max_bag_size or self.max_bag_duration)
            and f.message_count
            and (
                (self.max_bag_size and self._file_bytes >= self.max_bag_size)
                or (self.max_bag_duration and log_time - f.starting_time >= self.max_bag_duration)
            )
        ):
            self.split()
            f = self._file
            assert f is not None
        topic = self._topics[tid]
        try:
            self._add(topic.channel, log_time, data, publish_time)
        except OSError as e:
            raise BagError(f"Cannot write '{self.path / f.path}': {e.strerror or e}") from None
        topic.count += 1
        self._count += 1
        self._file_bytes += len(data) + _RECORD_OVERHEAD
        if f.message_count == 0 or log_time < f.starting_time:
            if f.message_count:
                f.duration += f.starting_time - log_time
            f.starting_time = log_time
        elif log_time - f.starting_time > f.duration:
            f.duration = log_time - f.starting_time
        f.message_count += 1
        if log_time < self._start:
            self._start = log_time
        if log_time > self._end:
            self._end = log_time

    def flush(self) -> None:
        """Put the chunk in progress on disk now (a crash then loses nothing written so far)."""
        if self._storage is not None:
            try:
                self._storage.flush_chunk()
            except OSError as e:
                raise BagError(f"Cannot write '{self._storage.path}': {e.strerror or e}") from None

    def metadata(self) -> BagMetadata:
        """The metadata as of now (what metadata.yaml will say if the bag closed now)."""
        empty = self._count == 0
        return BagMetadata(
            storage_identifier="mcap",
            duration=0 if empty else self._end - self._start,
            starting_time=self._start,
            message_count=self._count,
            topics_with_message_count=[TopicInformation(t.meta, t.count) for t in self._topics],
            relative_file_paths=[f.path for f in self._files],
            files=[
                FileInformation(f.path, f.starting_time, f.duration, f.message_count)
                for f in self._files
            ],
            custom_data=self.custom_data,
        )
