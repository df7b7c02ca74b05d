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

from ros2lite.bag.storage import StorageReader, StorageWriter
from ros2lite.bag.storage.mcap.read import McapStorageReader
from ros2lite.bag.storage.mcap.recover import is_complete, recover
from ros2lite.bag.storage.mcap.write import (
    COMPRESSIONS,
    DEFAULT_CHUNK_SIZE,
    PRESETS,
    McapStorageWriter,
)

__all__ = [
    "COMPRESSIONS",
    "DEFAULT_CHUNK_SIZE",
    "PRESETS",
    "McapStorageReader",
    "McapStorageWriter",
    "is_complete",
    "open_reader",
    "open_writer",
    "recover",
]


def open_reader(path: str) -> StorageReader:
    """The plugin's reader of one file."""
    return McapStorageReader(path)


def open_writer(
    path: str, *, compression: str = "none", chunk_size: int = DEFAULT_CHUNK_SIZE
) -> StorageWriter:
    """The plugin's writer of one new file."""
    return McapStorageWriter(path, compression=compression, chunk_size=chunk_size)
