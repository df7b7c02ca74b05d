"""Storage plugins: one module per file format, the same small interface for each.

A bag is a directory of files of one format. Readers give the topics, counts, definitions and
messages of one file; the mcap plugin also writes. The plugin names are rosbag2's.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any, Protocol

from ros2lite.bag.errors import BagError
from ros2lite.bag.metadata import BagMetadata, TopicMetadata

__all__ = [
    "PLUGINS",
    "BagError",
    "FileSummary",
    "StorageReader",
    "open_storage_reader",
    "plugin_for",
]


@dataclass
class FileSummary:
    """What one storage file knows about itself, read without touching message data where the
    format allows (MCAP summary section, SQL aggregates)."""

    topics: list[TopicMetadata]
    counts: dict[str, int]  # messages per topic
    message_count: int
    start: int | None  # first log time (ns), None when empty
    end: int | None
    definitions: dict[str, tuple[str, str]] = field(default_factory=dict)  # type → (enc, text)
    metadata: BagMetadata | None = None  # the last `rosbag2` record, if any
    complete: bool = True  # False: no summary, scanned up to a broken end
    ros_distro: str = ""


class StorageReader(Protocol):
    path: str

    def summary(self) -> FileSummary: ...

    def messages(
        self, topics: set[str] | None = None, start: int | None = None, stop: int | None = None
    ) -> Iterator[tuple[str, bytes, int, int]]: ...

    def close(self) -> None: ...


# storage id → (module, file extension); rosbag2's names
PLUGINS: dict[str, tuple[str, str]] = {
    "mcap": ("ros2lite.bag.storage.mcap", ".mcap"),
    "sqlite3": ("ros2lite.bag.storage.sqlite3", ".db3"),
}


def plugin_for(path: str) -> str | None:
    """The storage id owning a file, by extension."""
    for name, (_, ext) in PLUGINS.items():
        if path.endswith(ext):
            return name
    return None


def open_storage_reader(path: str, storage_id: str | None = None) -> Any:
    import importlib

    sid = storage_id or plugin_for(path)
    if sid not in PLUGINS:
        raise BagError(f"No storage plugin for '{path}' (known: {', '.join(PLUGINS)})")
    module = importlib.import_module(PLUGINS[sid][0])
    return module.open_reader(path)
