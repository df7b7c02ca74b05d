"""Recovering an MCAP file that has no summary (its recorder was killed, a copy cut short):
rewritten complete with every record that can be trusted.
"""

from __future__ import annotations

import contextlib
import os
from typing import TYPE_CHECKING, BinaryIO

from ros2lite.bag.storage.mcap.read import McapStorageReader
from ros2lite.bag.storage.mcap.scan import _scan
from ros2lite.bag.storage.mcap.write import DEFAULT_CHUNK_SIZE, library_name

if TYPE_CHECKING:
    from mcap.records import Metadata


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
        writer.start(profile="ros2", library=library_name())
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
        return reader.indexed
    finally:
        reader.close()
