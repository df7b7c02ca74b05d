"""ROS 1 `.bag` files as a storage plugin (`rosbag1`), read through `rosbags` (the optional
`ros1` extra): `bag info`, `play`, `echo`, `export`, `cut` and `convert` take them like any bag.

Each message is turned from ROS 1's serialization into ROS 2's CDR as it is read (rosbags'
converter: `std_msgs/Header` loses its `seq`, `time`/`duration` become builtin_interfaces), so
everything downstream sees a ROS 2 bag: type names in the `pkg/msg/Type` form, the types'
definitions (from the bag's own ROS 1 definitions, written as ROS 2 `.msg` text), a latched
topic offered TRANSIENT_LOCAL. The receive time is both the log and the publish time.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING

from ros2lite.bag.errors import BagError
from ros2lite.bag.metadata import TopicMetadata
from ros2lite.bag.storage import FileSummary, StorageReader
from ros2lite.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

if TYPE_CHECKING:
    from rosbags.interfaces import Connection
    from rosbags.rosbag1 import Reader as Ros1Reader
    from rosbags.typesys.store import Typestore

__all__ = ["Rosbag1Reader", "open_reader"]

INSTALL_HINT = "reading ROS 1 bags needs rosbags: pip install 'ros2lite[ros1]'"
# what rosbag2 offers for a topic ROS 1 recorded as latched
_LATCHED = QoSProfile(
    history=HistoryPolicy.KEEP_LAST,
    depth=1,
    reliability=ReliabilityPolicy.RELIABLE,
    durability=DurabilityPolicy.TRANSIENT_LOCAL,
)


class Rosbag1Reader:
    """One ROS 1 bag file, read as a ROS 2 one."""

    def __init__(self, path: str) -> None:
        try:
            from rosbags.rosbag1 import Reader, ReaderError
        except ImportError:
            raise BagError(f"'{path}': {INSTALL_HINT}") from None
        self.path = path
        self._reader: Ros1Reader = Reader(path)
        try:
            self._reader.open()
        except (ReaderError, OSError, ValueError, KeyError) as e:
            raise BagError(f"'{path}' is not a readable ROS 1 bag ({e})") from None
        self._converters: dict[int, Callable[[bytes], bytes]] = {}
        self._types: dict[str, str] = {}  # ROS 1 type name (as rosbags gives it) → ROS 2's
        self._summary: FileSummary | None = None
        self._build_types()

    def _build_types(self) -> None:
        """The bag's own definitions, a ROS 1 store and a ROS 2 one made from it (Header as
        ROS 2 has it), and a converter per connection."""
        from rosbags.convert.converter import STATIC_MSGTYPE_RENAMES, generate_message_converter
        from rosbags.typesys import Stores, TypesysError, get_types_from_msg, get_typestore

        source = get_typestore(Stores.ROS1_NOETIC)
        try:
            for conn in self._reader.connections:
                if conn.msgdef.data:
                    source.register(get_types_from_msg(conn.msgdef.data, conn.msgtype))
        except (TypesysError, ValueError, KeyError) as e:
            raise BagError(f"'{self.path}' holds a definition that does not parse ({e})") from None
        header = get_typestore(Stores.ROS2_JAZZY).fielddefs["std_msgs/msg/Header"]
        target = get_typestore(Stores.EMPTY)
        target.register({**source.fielddefs, "std_msgs/msg/Header": header})
        for name, new in STATIC_MSGTYPE_RENAMES.items():
            if name in source.fielddefs and new not in target.fielddefs:
                target.register({new: source.fielddefs[name]})
        self._target: Typestore = target
        cache: dict[str, object] = {}
        for conn in self._reader.connections:
            ros2 = STATIC_MSGTYPE_RENAMES.get(conn.msgtype, conn.msgtype)
            self._types[conn.msgtype] = ros2
            if ros2 not in target.fielddefs:
                continue  # no definition: its messages cannot be converted (said on reading)
            with contextlib.redirect_stdout(None):  # rosbags prints what it migrates
                convert = generate_message_converter(
                    source, target, conn.msgtype, ros2, cache, src_is2=False, dst_is2=True
                )
            self._converters[conn.id] = _as_bytes(convert)

    def close(self) -> None:
        """Close the file."""
        with contextlib.suppress(Exception):
            self._reader.close()

    def _topic(self, conn: Connection) -> TopicMetadata:
        latched = bool(getattr(conn.ext, "latching", 0))
        return TopicMetadata(
            name=conn.topic,
            type=self._types.get(conn.msgtype, conn.msgtype),
            serialization_format="cdr",
            offered_qos_profiles=[_LATCHED] if latched else [],
            type_description_hash="",  # a ROS 1 definition: no ROS 2 hash to claim
        )

    def summary(self) -> FileSummary:
        """Topics, counts and times from the bag's index (no message read)."""
        if self._summary is not None:
            return self._summary
        reader = self._reader
        topics: dict[str, TopicMetadata] = {}
        for conn in reader.connections:
            topics.setdefault(conn.topic, self._topic(conn))
        counts = {name: info.msgcount for name, info in reader.topics.items()}
        summary = FileSummary(list(topics.values()), {n: counts.get(n, 0) for n in topics})
        summary.message_count = reader.message_count
        if summary.message_count:
            summary.start, summary.end = (
                reader.start_time,
                max(reader.start_time, reader.end_time - 1),
            )
        summary.ros_distro = "noetic"
        for ros2 in set(self._types.values()):
            if ros2 in self._target.fielddefs:
                text, _ = self._target.generate_msgdef(ros2, ros_version=2)
                summary.definitions[ros2] = ("ros2msg", text)
        self._summary = summary
        return summary

    def messages(
        self, topics: set[str] | None = None, start: int | None = None, stop: int | None = None
    ) -> Iterator[tuple[str, bytes, int, int]]:
        """(topic, ROS 2 CDR bytes, time, time) in time order, `start <= t < stop`."""
        from rosbags.rosbag1 import ReaderError

        reader = self._reader
        conns = [c for c in reader.connections if topics is None or c.topic in topics]
        if not conns:
            return
        missing = {c.topic for c in conns if c.id not in self._converters}
        if missing:
            raise BagError(
                f"'{self.path}' has no definition of the type of {', '.join(sorted(missing))}"
            )
        converters = self._converters
        try:
            for conn, t, raw in reader.messages(conns, start, stop):
                yield conn.topic, converters[conn.id](raw), t, t
        except (ReaderError, ValueError, KeyError, IndexError) as e:
            raise BagError(f"'{self.path}' is damaged ({e or type(e).__name__})") from None


def _as_bytes(convert: Callable[[bytes], memoryview]) -> Callable[[bytes], bytes]:
    def run(raw: bytes) -> bytes:
        return bytes(convert(raw))

    return run


def open_reader(path: str) -> StorageReader:
    """The plugin's reader of one file."""
    return Rosbag1Reader(path)
