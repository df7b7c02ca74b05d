"""Reading a bag: a rosbag2 directory (any metadata version, with or without metadata.yaml) or
a bare `.mcap`/`.db3` file, as one stream of messages in log-time order.

Messages are decoded with the local type when it is the one the bag was recorded with (same
RIHS01 hash, or the bag does not say), else with the definitions stored in the bag itself; a
type neither knows comes out as CDR bytes.
"""

from __future__ import annotations

import heapq
import os
import re
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING

from ros2lite.bag.errors import BagError, MetadataError
from ros2lite.bag.metadata import (
    METADATA_FILENAME,
    BagMetadata,
    FileInformation,
    TopicInformation,
    TopicMetadata,
    read_metadata_file,
)
from ros2lite.bag.storage import FileSummary, StorageReader, open_storage_reader, plugin_for

if TYPE_CHECKING:
    from ros2lite.bag.definitions import BagTypes
    from ros2lite.interfaces import Message
    from ros2lite.interfaces.registry import Registry

__all__ = ["Reader", "bag_files", "metadata_from_files"]

_SPLIT_INDEX = re.compile(r".+_(\d+)\.\w+$")


def bag_files(directory: Path) -> list[Path]:
    """Storage files of a bag directory without metadata.yaml, in split order: names ending
    `_<N>.<ext>` by N (what `ros2 bag reindex` accepts), then any other storage file."""
    found = [p for p in directory.iterdir() if p.is_file() and plugin_for(p.name)]

    def key(p: Path) -> tuple[int, int, str]:
        m = _SPLIT_INDEX.match(p.name)
        return (0, int(m.group(1)), p.name) if m else (1, 0, p.name)

    return sorted(found, key=key)


def metadata_from_files(
    names: list[str], summaries: list[FileSummary], storage_id: str
) -> BagMetadata:
    """Bag metadata rebuilt from its files alone (what `reindex` writes): counts and times
    from the storage, compression, custom data and distro from the last `rosbag2` record."""
    topics: dict[str, TopicInformation] = {}
    files = []
    start, end, total = None, None, 0
    record = None
    distro = ""
    for name, s in zip(names, summaries, strict=True):
        for t in s.topics:
            info = topics.setdefault(t.name, TopicInformation(t, 0))
            info.message_count += s.counts.get(t.name, 0)
        total += s.message_count
        if s.start is not None and s.end is not None:
            start = s.start if start is None else min(start, s.start)
            end = s.end if end is None else max(end, s.end)
            files.append(FileInformation(name, s.start, s.end - s.start, s.message_count))
        else:
            files.append(FileInformation(name, message_count=s.message_count))
        record = s.metadata or record
        distro = s.ros_distro or distro
    m = BagMetadata(
        storage_identifier=storage_id,
        duration=0 if start is None or end is None else end - start,
        message_count=total,
        topics_with_message_count=list(topics.values()),
        relative_file_paths=list(names),
        files=files,
        ros_distro=distro or (record.ros_distro if record else ""),
    )
    if start is not None:
        m.starting_time = start
    if record is not None:
        m.compression_format = record.compression_format
        m.compression_mode = record.compression_mode
        m.custom_data = record.custom_data
    return m


class Reader:
    """A bag, read as `(topic, message, log_time_ns)`.

    >>> with Reader('my_bag') as bag:
    ...     for topic, msg, t in bag:
    ...         print(topic, t, msg)

    `messages(raw=True)` yields CDR bytes instead; `raw_messages()` also gives the publish
    time. `metadata` comes from metadata.yaml when there is one, else from the files' own
    summaries, so opening a bag reads no message data.
    """

    def __init__(self, path: str | os.PathLike[str], storage_id: str | None = None) -> None:
        self.path = Path(path)
        self._storage_id = storage_id
        self._readers: dict[Path, StorageReader] = {}
        self._summaries: dict[Path, FileSummary] = {}
        self._types: BagTypes | None = None
        self._decoders: dict[str, Callable[[bytes], Message | bytes]] = {}
        self._told: set[Path] = set()  # files whose damage was said (by shortfalls())
        if not self.path.exists():
            raise BagError(f"Bag path '{path}' does not exist!")
        self.directory: Path
        self.files: list[Path]
        meta: BagMetadata | None = None
        if self.path.is_file() and self.path.name == METADATA_FILENAME:
            self.path = self.path.parent
        if self.path.is_dir():
            self.directory = self.path
            yaml_path = self.path / METADATA_FILENAME
            if yaml_path.is_file():
                try:
                    meta = read_metadata_file(yaml_path)
                except MetadataError as e:
                    raise BagError(f"Bad metadata in '{yaml_path}': {e}") from None
                self.files = [self._resolve(p) for p in meta.relative_file_paths]
            else:
                self.files = bag_files(self.path)
                if not self.files:
                    raise BagError(f"No bag files (.mcap or .db3) in '{path}'")
        else:
            if plugin_for(self.path.name) is None:
                raise BagError(
                    f"'{path}' is not a bag (expected a directory, a .mcap or a .db3 file)"
                )
            self.directory = self.path.parent
            self.files = [self.path]
        for f in self.files:
            if f.name.endswith(".zstd"):
                raise BagError(
                    f"'{f}' is compressed per file (compression_mode FILE); "
                    f"decompress it first (zstd -d)"
                )
        self.metadata: BagMetadata = meta if meta is not None else self._metadata_from_files()

    def _resolve(self, relative: str) -> Path:
        p = self.path / relative
        if not p.exists():
            # metadata before version 4 prefixed the bag directory itself
            alt = self.path / Path(relative).name
            if alt.exists():
                return alt
            raise BagError(f"Bag file '{p}' listed in metadata.yaml does not exist")
        return p

    def _storage_for(self, f: Path) -> str:
        sid = self._storage_id or plugin_for(f.name)
        if sid is None:
            raise BagError(f"No storage plugin for '{f}'")
        return sid

    def _reader(self, f: Path) -> StorageReader:
        r = self._readers.get(f)
        if r is None:
            r = self._readers[f] = open_storage_reader(str(f), self._storage_for(f))
        return r

    def summary(self, f: Path) -> FileSummary:
        """What the file `f` of the bag says about itself (read once)."""
        s = self._summaries.get(f)
        if s is None:
            s = self._summaries[f] = self._reader(f).summary()
        return s

    def _metadata_from_files(self) -> BagMetadata:
        summaries = [self.summary(f) for f in self.files]
        return metadata_from_files(
            [f.name for f in self.files], summaries, self._storage_for(self.files[0])
        )

    def close(self) -> None:
        """Close the files opened so far."""
        for r in self._readers.values():
            r.close()
        self._readers.clear()

    def __enter__(self) -> Reader:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()

    def __iter__(self) -> Iterator[tuple[str, Message | bytes, int]]:
        return self.messages()

    # -- topics --------------------------------------------------------------------------------
    @property
    def topics(self) -> list[TopicMetadata]:
        """The bag's topics, in metadata order."""
        return [t.topic_metadata for t in self.metadata.topics_with_message_count]

    def definition(self, type_name: str) -> tuple[str, str] | None:
        """(schema encoding, text) of a type as the bag's files carry it, if they do."""
        for f in self.files:
            try:
                found = self.summary(f).definitions.get(type_name)
            except BagError:
                continue
            if found is not None and (found[0] or found[1]):
                return found
        return None

    def topic(self, name: str) -> TopicMetadata | None:
        """One topic's metadata, if the bag has it."""
        info = self.metadata.topic(name)
        return info.topic_metadata if info is not None else None

    @property
    def message_count(self) -> int:
        """Messages in the whole bag."""
        return self.metadata.message_count

    @property
    def start_time(self) -> int:
        """Log time (ns) of the first message."""
        return self.metadata.starting_time

    @property
    def end_time(self) -> int:
        """Log time (ns) of the last message."""
        return self.metadata.starting_time + self.metadata.duration

    def shortfalls(self) -> list[str]:
        """One line per file that cannot give what metadata.yaml promises (a recording cut
        short, a truncated copy): how many messages were promised and how many are readable.
        Reads only summaries, except for files without one (those are scanned)."""
        promised = {Path(f.path).name: f.message_count for f in self.metadata.files}
        out = []
        for f in self.files:
            try:
                summary = self.summary(f)
            except BagError as e:
                out.append(f"'{f}' cannot be read: {e}")
                continue
            self._told.add(f)
            out.extend(summary.problems)
            want = promised.get(f.name)
            if want is not None and summary.message_count < want:
                out.append(
                    f"'{f}' is incomplete: metadata.yaml promises {want} messages, "
                    f"{summary.message_count} are readable (a recording cut short or a "
                    "truncated copy; `ros2lite bag reindex` rewrites the metadata)"
                )
        return out

    # -- messages ------------------------------------------------------------------------------
    def raw_messages(
        self, topics: Iterable[str] | None = None, start: int | None = None, stop: int | None = None
    ) -> Iterator[tuple[str, bytes, int, int]]:
        """(topic, CDR bytes, log_time, publish_time) in log-time order across all files,
        with `start <= log_time < stop`."""
        wanted = set(topics) if topics is not None else None
        self._tell_damage()
        streams = [self._reader(f).messages(wanted, start, stop) for f in self.files]
        if len(streams) == 1:
            yield from streams[0]
            return
        yield from heapq.merge(*streams, key=lambda m: m[2])

    def _tell_damage(self) -> None:
        """Say once, as a warning, what damaged files lost, unless `shortfalls()` (which
        the CLI renders itself) already did: a damaged bag is never read in silence."""
        from ros2lite.logging import get_logger

        for f in self.files:
            if f in self._told:
                continue
            self._told.add(f)
            try:
                problems = self.summary(f).problems
            except BagError:
                continue  # opening its messages says why
            for line in problems:
                get_logger("rosbag2_storage").warn(line)

    def messages(
        self,
        topics: Iterable[str] | None = None,
        start: int | None = None,
        stop: int | None = None,
        *,
        raw: bool = False,
    ) -> Iterator[tuple[str, Message | bytes, int]]:
        """(topic, message, log_time): message objects, or CDR bytes with `raw=True` or for
        a type that cannot be decoded here."""
        for topic, data, log_time, _ in self.raw_messages(topics, start, stop):
            yield topic, data if raw else self.decode(topic, data), log_time

    def decode(self, topic: str, data: bytes) -> Message | bytes:
        """One message of `topic` as `messages()` gives it: decoded with the type it was
        recorded with, or the CDR bytes when no definition here or in the bag fits."""
        decode = self._decoders.get(topic)
        if decode is None:
            decode = self._decoders[topic] = self._decoder(topic)
        return decode(data)

    def deserialize(self, data: bytes, type_name: str) -> Message:
        """Decode CDR bytes of a type the bag holds (its own definition if need be)."""
        from ros2lite.interfaces.cdr import codec
        from ros2lite.interfaces.registry import normalize_name

        return codec(normalize_name(type_name), self._registry_for(type_name, "")).deserialize(data)

    def bag_types(self) -> BagTypes:
        """The type definitions the bag itself carries (every file's schemas), read once."""
        if self._types is None:
            from ros2lite.bag.definitions import BagTypes

            types = BagTypes()
            for f in self.files:
                try:
                    defs = self.summary(f).definitions
                except BagError:
                    continue
                for type_name, (encoding, text) in defs.items():
                    types.add(type_name, encoding, text)
            self._types = types
        return self._types

    def _registry_for(self, type_name: str, bag_hash: str) -> Registry:
        """The local registry when it has this very type, else the bag's definitions."""
        from ros2lite.interfaces import InterfaceError, type_hash
        from ros2lite.interfaces.registry import default_registry, normalize_name

        full = normalize_name(type_name)
        try:
            local = type_hash(full)
        except (InterfaceError, LookupError, ValueError):
            local = None
        types = self.bag_types()
        if local is not None and (not bag_hash or bag_hash == local or full not in types.known):
            return default_registry()
        if full in types.known:
            return types
        return default_registry()

    def _decoder(self, topic: str) -> Callable[[bytes], Message | bytes]:
        from ros2lite.interfaces import InterfaceError
        from ros2lite.interfaces.cdr import codec
        from ros2lite.interfaces.registry import normalize_name

        meta = self.topic(topic)
        if meta is None or meta.serialization_format != "cdr" or not meta.type:
            return _as_bytes
        try:
            c = codec(
                normalize_name(meta.type), self._registry_for(meta.type, meta.type_description_hash)
            )
        except (InterfaceError, LookupError, ValueError):
            return _as_bytes

        def decode(data: bytes) -> Message | bytes:
            try:
                return c.deserialize(data)
            except ValueError:
                return data  # not this type after all (e.g. garbage on the topic)

        return decode


def _as_bytes(data: bytes) -> bytes:
    return data
