"""The `sqlite3` storage plugin (read only): rosbag2's `.db3` files, through the stdlib.

Tables: `topics` (name, type, serialization_format, offered_qos_profiles[, type_description_hash]),
`messages` (topic_id, timestamp, data) and, in newer files, `message_definitions` and `metadata`.
A db3 message has one timestamp: it is both the log and the publish time.
"""

from __future__ import annotations

import contextlib
import os
import sqlite3
from collections.abc import Iterator
from urllib.parse import quote

from ros2lite.bag.errors import BagError, MetadataError
from ros2lite.bag.metadata import TopicMetadata, parse_metadata, parse_qos_list
from ros2lite.bag.storage import FileSummary, StorageReader

__all__ = ["Sqlite3StorageReader", "open_reader"]


# a message row as rosbag2 writes it: an integer time and a blob (R5-B5: a TEXT timestamp
# or data broke arithmetic and decoding); the others are counted and skipped
_SOUND_ROW = "typeof(timestamp) = 'integer' AND typeof(data) = 'blob'"
_NAME_LIMIT = 4096


class Sqlite3StorageReader:
    """One `.db3` file of an older rosbag2 bag, read with SQL."""

    def __init__(self, path: str) -> None:

        self.path = path
        if not os.path.isfile(path):
            raise BagError(f"Cannot open '{path}': No such file")
        self._db = self._connect(path)
        try:
            self._check_columns()
        except BagError:
            self._db.close()
            raise
        except sqlite3.DatabaseError as e:
            self._db.close()
            raise BagError(f"'{path}' is not a readable sqlite3 bag ({e})") from None

    def _check_columns(self) -> None:
        """A table of a bag stores its values: a generated column (computed on read, e.g. a
        500 MB topic name or a 1 GB blob per row, R5-B5) is no rosbag2 bag's, and refused
        before anything reads it."""
        for table in ("topics", "messages"):
            for row in self._db.execute(f"PRAGMA table_xinfo({table})"):
                if row[6] in (2, 3):  # hidden: 2 virtual, 3 stored generated column
                    raise BagError(
                        f"'{self.path}': column {table}.{str(row[1])[:64]} is generated, "
                        "not stored: not a rosbag2 bag"
                    )

    @staticmethod
    def _connect(path: str) -> sqlite3.Connection:

        uri = "file:" + quote(path)
        # read-only; a bag in a read-only directory (no -shm can be made) is opened as
        # immutable, which is what a finished bag is
        for suffix in ("?mode=ro", "?mode=ro&immutable=1"):
            try:
                db = sqlite3.connect(uri + suffix, uri=True, check_same_thread=False)
                db.execute("SELECT count(*) FROM sqlite_master").fetchone()
                return db
            except sqlite3.DatabaseError as e:
                error = e
        raise BagError(f"'{path}' is not a readable sqlite3 bag ({error})")

    def close(self) -> None:
        """Close the database."""
        self._db.close()

    def _tables(self) -> set[str]:
        return {r[0] for r in self._db.execute("SELECT name FROM sqlite_master WHERE type='table'")}

    def _topic_rows(self) -> list[tuple[int, TopicMetadata]]:
        cols = [r[1] for r in self._db.execute("PRAGMA table_info(topics)")]
        has_hash = "type_description_hash" in cols
        # text of sane size only: a name or type of another type or size is skipped
        rows = self._db.execute(
            "SELECT id, name, type, serialization_format, offered_qos_profiles"
            + (", type_description_hash" if has_hash else "")
            + " FROM topics WHERE typeof(name) = 'text' AND typeof(type) = 'text'"
            f" AND length(name) <= {_NAME_LIMIT} AND length(type) <= {_NAME_LIMIT}"
            " ORDER BY id"
        )
        out = []
        for row in rows:
            try:
                qos = parse_qos_list(row[4])
            except MetadataError:
                qos = []
            out.append(
                (
                    row[0],
                    TopicMetadata(
                        name=row[1],
                        type=row[2],
                        serialization_format=row[3],
                        offered_qos_profiles=qos,
                        type_description_hash=(row[5] or "") if has_hash else "",
                    ),
                )
            )
        return out

    def summary(self) -> FileSummary:
        """Topics, counts and times from SQL aggregates (no message data read)."""
        try:
            return self._summary()
        except sqlite3.DatabaseError as e:
            raise BagError(f"'{self.path}' is not a readable sqlite3 bag ({e})") from None

    def _summary(self) -> FileSummary:
        tables = self._tables()
        if not {"topics", "messages"} <= tables:
            raise BagError(f"'{self.path}' is not a rosbag2 sqlite3 file (no topics/messages)")
        topics = self._topic_rows()
        by_id = {tid: t for tid, t in topics}
        summary = FileSummary([t for _, t in topics], {t.name: 0 for _, t in topics})
        for tid, n, lo, hi in self._db.execute(
            f"SELECT topic_id, count(*), min(timestamp), max(timestamp) FROM messages "
            f"WHERE {_SOUND_ROW} GROUP BY topic_id"
        ):
            summary.add(by_id[tid].name if tid in by_id else None, n, lo, hi)
        (odd,) = self._db.execute(
            f"SELECT count(*) FROM messages WHERE NOT ({_SOUND_ROW})"
        ).fetchone()
        if odd:
            summary.problems.append(
                f"'{self.path}': {odd} message row(s) whose timestamp is not an integer or whose "
                "data is not a blob; skipped"
            )
        if "message_definitions" in tables:
            for type_name, encoding, text in self._db.execute(
                "SELECT topic_type, encoding, encoded_message_definition FROM message_definitions"
            ):
                summary.definitions[type_name] = (encoding, text)
        if "metadata" in tables:
            with contextlib.suppress(sqlite3.DatabaseError, MetadataError):
                row = self._db.execute(
                    "SELECT metadata FROM metadata ORDER BY id DESC LIMIT 1"
                ).fetchone()
                if row:
                    summary.metadata = parse_metadata(row[0], top_key=False)
                    summary.ros_distro = summary.metadata.ros_distro
        if not summary.ros_distro and "schema" in tables:
            with contextlib.suppress(sqlite3.DatabaseError):
                row = self._db.execute("SELECT ros_distro FROM schema").fetchone()
                summary.ros_distro = row[0] if row else ""
        return summary

    def messages(
        self, topics: set[str] | None = None, start: int | None = None, stop: int | None = None
    ) -> Iterator[tuple[str, bytes, int, int]]:
        """(topic, data, log time, log time) in time order, `start <= t < stop`."""
        names = {tid: t.name for tid, t in self._topic_rows()}
        query = "SELECT topic_id, timestamp, data FROM messages"
        where: list[str] = [_SOUND_ROW]
        args: list[int] = []
        if start is not None:
            where.append("timestamp >= ?")
            args.append(start)
        if stop is not None:
            where.append("timestamp < ?")
            args.append(stop)
        query += " WHERE " + " AND ".join(where)
        query += " ORDER BY timestamp, id"
        try:
            for tid, stamp, data in self._db.execute(query, args):
                name = names.get(tid)
                if name is not None and (topics is None or name in topics):
                    yield name, bytes(data), stamp, stamp
        except sqlite3.DatabaseError as e:
            raise BagError(f"'{self.path}' is not a readable sqlite3 bag ({e})") from None


def open_reader(path: str) -> StorageReader:
    """The plugin's reader of one file."""
    return Sqlite3StorageReader(path)
