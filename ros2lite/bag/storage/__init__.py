"""Storage plugins: one module per file format, the same small interface for each.

A bag is a directory of files of one format. Readers give the topics, counts, definitions and
messages of one file (:class:`StorageReader`, what :class:`ros2lite.bag.reader.Reader` uses);
the mcap plugin also writes (:class:`StorageWriter`, what :class:`ros2lite.bag.writer.Writer`
uses). The plugin names are rosbag2's.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import Protocol

from ros2lite.bag.errors import BagError
from ros2lite.bag.metadata import BagMetadata, TopicMetadata

__all__ = [
    "PLUGINS",
    "BagError",
    "FileSummary",
    "StorageReader",
    "StorageWriter",
    "open_storage_reader",
    "plugin_for",
]


@dataclass
class FileSummary:
    """What one storage file knows about itself, read without touching message data where the
    format allows (MCAP summary section, SQL aggregates)."""

    topics: list[TopicMetadata]
    counts: dict[str, int]  # messages per topic
    message_count: int = 0
    start: int | None = None  # first log time (ns), None when empty
    end: int | None = None
    definitions: dict[str, tuple[str, str]] = field(default_factory=dict)  # type → (enc, text)
    metadata: BagMetadata | None = None  # the last `rosbag2` record, if any
    complete: bool = True  # False: no summary, scanned up to a broken end
    ros_distro: str = ""
    problems: list[str] = field(default_factory=list)  # what a scan lost, one line each

    def add(self, topic: str | None, count: int, first: int, last: int) -> None:
        """Count `count` messages of `topic` (None: of a topic the file does not list), logged
        from `first` to `last` (ns): how a reader adds up aggregates or a scan."""
        if topic is not None:
            self.counts[topic] += count
        self.message_count += count
        self.start = first if self.start is None or first < self.start else self.start
        self.end = last if self.end is None or last > self.end else self.end


class StorageReader(Protocol):
    """One file of a bag, open for reading."""

    path: str

    def summary(self) -> FileSummary:
        """Topics, counts, times and definitions of the file (cheap where the format can)."""
        ...

    def messages(
        self, topics: set[str] | None = None, start: int | None = None, stop: int | None = None
    ) -> Iterator[tuple[str, bytes, int, int]]:
        """(topic, CDR bytes, log time, publish time) in log-time order, `start <= t < stop`,
        of the given topics (None: all)."""
        ...

    def close(self) -> None:
        """Release the file."""
        ...


class StorageWriter(Protocol):
    """One file of a bag being written: schemas and channels first, then messages."""

    path: str

    def add_message(self, channel_id: int, log_time: int, data: bytes, publish_time: int) -> None:
        """One message on a registered channel (the hot path: may be a plain callable
        attribute, so that writing a message is one call)."""
        ...

    @property
    def size(self) -> int:
        """Bytes handed to the OS so far."""
        ...

    def add_schema(self, type_name: str, encoding: str, text: str) -> int:
        """Register a type's definition (once per type); its schema id."""
        ...

    def add_channel(self, topic: TopicMetadata, schema_id: int) -> int:
        """Register a topic with its QoS and type hash; its channel id."""
        ...

    def add_rosbag2_metadata(self, metadata: BagMetadata) -> None:
        """Store the bag's metadata as known now (rosbag2 repeats it in every file)."""
        ...

    def flush_chunk(self) -> None:
        """Put what is buffered on disk now."""
        ...

    def close(self, metadata: BagMetadata | None = None) -> None:
        """Finish the file (with the final metadata); complete and readable after this."""
        ...

    def abandon(self) -> None:
        """Stop without finishing (after a write error); keep what reached the disk."""
        ...


# storage id → (module, file extension); rosbag2's names
PLUGINS: dict[str, tuple[str, str]] = {
    "mcap": ("ros2lite.bag.storage.mcap", ".mcap"),
    "sqlite3": ("ros2lite.bag.storage.sqlite3", ".db3"),
    "rosbag1": ("ros2lite.bag.rosbag1", ".bag"),  # ROS 1 bags, read through rosbags
}


def plugin_for(path: str) -> str | None:
    """The storage id owning a file, by extension."""
    for name, (_, ext) in PLUGINS.items():
        if path.endswith(ext):
            return name
    return None


def open_storage_reader(path: str, storage_id: str | None = None) -> StorageReader:
    """A reader of one file, by its storage id (or its extension)."""
    sid = storage_id or plugin_for(path)
    if sid not in PLUGINS:
        raise BagError(f"No storage plugin for '{path}' (known: {', '.join(PLUGINS)})")
    module = importlib.import_module(PLUGINS[sid][0])
    open_reader: Callable[[str], StorageReader] = module.open_reader
    return open_reader(path)
