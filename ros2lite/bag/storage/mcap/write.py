"""Writing rosbag2's MCAP layout: profile `ros2`, chunked, every index, statistics and summary
(rosbag2's defaults), one `ros2msg` schema per type, one channel per topic carrying
`offered_qos_profiles` and `topic_type_hash`, and `rosbag2` metadata records. The file is written
without a user-space buffer, so each finished chunk is in the OS the moment the writer lets go of
it: a recorder killed outright leaves every complete chunk readable.
"""

from __future__ import annotations

import os

from ros2lite.bag.errors import BagError
from ros2lite.bag.metadata import BagMetadata, TopicMetadata, dump_metadata, dump_qos_list

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


def library_name() -> str:
    """The MCAP header's library field: ros2lite and its version."""
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
            self._writer.start(profile="ros2", library=library_name())
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
