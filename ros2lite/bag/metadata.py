"""rosbag2's bag metadata: the `metadata.yaml` beside the files and the `rosbag2` MCAP record.

One dataclass tree serves every metadata version rosbag2 ever wrote (4-9 are read; 9 is
written). The YAML is emitted by hand in yaml-cpp's block layout, key order included, because
rosbag2 and rosbags parse it strictly and people diff it; reading goes through `yaml.safe_load`.
"""

from __future__ import annotations

import json
import os
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

from ros2lite.bag.errors import MetadataError
from ros2lite.duration import Duration
from ros2lite.pkg.distro import ros_distro
from ros2lite.qos import (
    DURATION_INFINITE,
    DurabilityPolicy,
    HistoryPolicy,
    LivelinessPolicy,
    QoSProfile,
    ReliabilityPolicy,
)
from ros2lite.util.files import ReadRefused, read_text_bounded, replace_file
from ros2lite.util.safe_yaml import YamlInputError, load

__all__ = [
    "EMPTY_STARTING_TIME",
    "METADATA_FILENAME",
    "METADATA_VERSION",
    "BagMetadata",
    "FileInformation",
    "MetadataError",
    "TopicInformation",
    "TopicMetadata",
    "dump_metadata",
    "dump_qos_list",
    "parse_metadata",
    "parse_qos_list",
    "read_metadata_file",
    "write_metadata_file",
]

METADATA_FILENAME = "metadata.yaml"
METADATA_VERSION = 9
# what rosbag2 writes as the start of a bag that has no message yet (INT64_MAX)
EMPTY_STARTING_TIME = 2**63 - 1


@dataclass
class TopicMetadata:
    """One topic of a bag: what rosbag2 keeps per topic, QoS as offered by its publishers."""

    name: str
    type: str
    serialization_format: str = "cdr"
    offered_qos_profiles: list[QoSProfile] = field(default_factory=list)
    type_description_hash: str = ""


@dataclass
class TopicInformation:
    """One topic of a bag and how many messages it has."""

    topic_metadata: TopicMetadata
    message_count: int = 0


@dataclass
class FileInformation:
    """One file of a bag: its path, time span and message count."""

    path: str
    starting_time: int = EMPTY_STARTING_TIME  # ns since the epoch
    duration: int = 0  # ns
    message_count: int = 0


@dataclass
class BagMetadata:
    """metadata.yaml (rosbag2's `rosbag2_bagfile_information`) as data."""

    version: int = METADATA_VERSION
    storage_identifier: str = "mcap"
    duration: int = 0  # ns, last minus first log time
    starting_time: int = EMPTY_STARTING_TIME  # ns since the epoch
    message_count: int = 0
    topics_with_message_count: list[TopicInformation] = field(default_factory=list)
    compression_format: str = ""
    compression_mode: str = ""
    relative_file_paths: list[str] = field(default_factory=list)
    files: list[FileInformation] = field(default_factory=list)
    custom_data: dict[str, str] | None = None
    ros_distro: str = field(default_factory=ros_distro)  # the distro we speak, as recorded

    def topic(self, name: str) -> TopicInformation | None:
        """The entry of one topic, if the bag has it."""
        for info in self.topics_with_message_count:
            if info.topic_metadata.name == name:
                return info
        return None


# -- QoS -----------------------------------------------------------------------------------------

# Durations older rosbag2 versions (Foxy era) wrote for "infinite"
_LEGACY_INFINITE = {(2147483647, 4294967295), (2147483647, 2147483647)}


def _duration_dict(d: Duration) -> dict[str, int]:
    return {"sec": d.sec, "nsec": d.nsec}


if TYPE_CHECKING:
    from ros2lite.qos import _Policy

_P = TypeVar("_P", bound="_Policy")


def qos_to_dict(q: QoSProfile, names: bool) -> dict[str, object]:
    """One offered QoS profile as rosbag2 writes it (policy names, or numbers)."""

    def policy(p: _Policy) -> str | int:
        return p.short_key if names else int(p)

    return {
        "history": policy(q.history),
        "depth": q.depth,
        "reliability": policy(q.reliability),
        "durability": policy(q.durability),
        "deadline": _duration_dict(q.deadline),
        "lifespan": _duration_dict(q.lifespan),
        "liveliness": policy(q.liveliness),
        "liveliness_lease_duration": _duration_dict(q.liveliness_lease_duration),
        "avoid_ros_namespace_conventions": False,
    }


def _policy(cls: type[_P], value: object, what: str) -> _P:
    if isinstance(value, bool):
        raise MetadataError(f"bad QoS {what}: {value!r}")
    if isinstance(value, int):
        try:
            return cls(value)
        except ValueError:
            raise MetadataError(f"bad QoS {what}: {value!r}") from None
    try:
        return cls.from_short_key(str(value))
    except ValueError:
        raise MetadataError(f"bad QoS {what}: {value!r}") from None


def _duration(value: object, what: str) -> Duration:
    if value is None:
        return Duration()
    if not isinstance(value, dict):
        raise MetadataError(f"bad QoS {what}: {value!r}")
    try:
        sec, nsec = int(value.get("sec", 0)), int(value.get("nsec", 0))
    except (TypeError, ValueError):
        raise MetadataError(f"bad QoS {what}: {value!r}") from None
    if (sec, nsec) in _LEGACY_INFINITE:
        return DURATION_INFINITE
    ns = sec * 1_000_000_000 + nsec
    if ns >= DURATION_INFINITE.nanoseconds or ns < 0:
        return DURATION_INFINITE
    return Duration(nanoseconds=ns)


def qos_from_dict(d: object) -> QoSProfile:
    """A profile from one entry of `offered_qos_profiles` (integer or named enums)."""
    if not isinstance(d, dict):
        raise MetadataError(f"bad QoS profile: {d!r}")
    try:
        depth = int(d.get("depth", 0))
    except (TypeError, ValueError):
        raise MetadataError(f"bad QoS depth: {d.get('depth')!r}") from None
    return QoSProfile(
        history=_policy(HistoryPolicy, d.get("history", 3), "history"),
        depth=max(depth, 0),
        reliability=_policy(ReliabilityPolicy, d.get("reliability", 3), "reliability"),
        durability=_policy(DurabilityPolicy, d.get("durability", 3), "durability"),
        deadline=_duration(d.get("deadline"), "deadline"),
        lifespan=_duration(d.get("lifespan"), "lifespan"),
        liveliness=_policy(LivelinessPolicy, d.get("liveliness", 4), "liveliness"),
        liveliness_lease_duration=_duration(
            d.get("liveliness_lease_duration"), "liveliness lease duration"
        ),
    )


def parse_qos_list(value: object) -> list[QoSProfile]:
    """`offered_qos_profiles` in any form rosbag2 wrote: a YAML string (v4-8 and channel
    metadata), a list (v9), or empty."""
    if value is None or value == "":
        return []
    if isinstance(value, str):
        try:
            value = load(value, "offered_qos_profiles")
        except YamlInputError as e:
            raise MetadataError(str(e)) from None
        if value is None:
            return []
    if not isinstance(value, list):
        raise MetadataError(f"bad offered_qos_profiles: {value!r}")
    return [qos_from_dict(d) for d in value]


def dump_qos_list(profiles: list[QoSProfile], names: bool = True) -> str:
    """The channel-metadata string: the profile list in block YAML, no trailing newline."""
    if not profiles:
        return ""
    return "\n".join(_emit([qos_to_dict(q, names) for q in profiles], 0))


# -- YAML emission in yaml-cpp's block style ----------------------------------------------------

_PLAIN = re.compile(r"^[A-Za-z_/.][A-Za-z0-9_./:\-]*$")
_RESERVED = {"true", "false", "yes", "no", "on", "off", "null", "y", "n", "~"}


def _scalar(value: object) -> str:
    if value is None:
        return "~"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    text = str(value)
    if text == "":
        return '""'
    if _PLAIN.match(text) and text.lower() not in _RESERVED:
        return text
    return json.dumps(text, ensure_ascii=False)


def _emit(value: Mapping[str, object] | Sequence[object], indent: int) -> list[str]:
    """Lines of a mapping or sequence at `indent` spaces (yaml-cpp: sequences under a key
    are indented two more, empty ones written `[]`, empty maps `{}`)."""
    pad = " " * indent
    lines: list[str] = []
    if isinstance(value, dict):
        for key, item in value.items():
            if isinstance(item, dict) and item:
                lines.append(f"{pad}{key}:")
                lines += _emit(item, indent + 2)
            elif isinstance(item, list):
                lines.append(f"{pad}{key}:")
                lines += _emit(item, indent + 2) if item else [f"{pad}  []"]
            elif isinstance(item, dict):
                lines.append(f"{pad}{key}: {{}}")
            else:
                lines.append(f"{pad}{key}: {_scalar(item)}")
        return lines
    for item in value:
        if isinstance(item, (dict, list)) and item:
            inner = _emit(item, indent + 2)
            lines.append(f"{pad}- {inner[0][indent + 2 :]}")
            lines += inner[1:]
        else:
            lines.append(f"{pad}- {_scalar(item)}")
    return lines


def _as_tree(m: BagMetadata) -> dict[str, object]:
    """The v9 key order of rosbag2's encoder."""
    topics = []
    for info in m.topics_with_message_count:
        t = info.topic_metadata
        topics.append(
            {
                "topic_metadata": {
                    "name": t.name,
                    "type": t.type,
                    "serialization_format": t.serialization_format,
                    "offered_qos_profiles": [qos_to_dict(q, True) for q in t.offered_qos_profiles],
                    "type_description_hash": t.type_description_hash,
                },
                "message_count": info.message_count,
            }
        )
    return {
        "version": METADATA_VERSION,
        "storage_identifier": m.storage_identifier,
        "duration": {"nanoseconds": m.duration},
        "starting_time": {"nanoseconds_since_epoch": m.starting_time},
        "message_count": m.message_count,
        "topics_with_message_count": topics,
        "compression_format": m.compression_format,
        "compression_mode": m.compression_mode,
        "relative_file_paths": list(m.relative_file_paths),
        "files": [
            {
                "path": f.path,
                "starting_time": {"nanoseconds_since_epoch": f.starting_time},
                "duration": {"nanoseconds": f.duration},
                "message_count": f.message_count,
            }
            for f in m.files
        ],
        "custom_data": dict(m.custom_data) if m.custom_data else None,
        "ros_distro": m.ros_distro,
    }


def dump_metadata(m: BagMetadata, *, top_key: bool = True) -> str:
    """metadata.yaml text (v9), or with `top_key=False` the `serialized_metadata` string of
    the MCAP `rosbag2` record."""
    tree = _as_tree(m)
    if top_key:
        return "\n".join(["rosbag2_bagfile_information:", *_emit(tree, 2)]) + "\n"
    return "\n".join(_emit(tree, 0)) + "\n"


# -- parsing ------------------------------------------------------------------------------------


def _require(d: dict[str, Any], key: str, version: int) -> Any:  # YAML: checked by the caller
    if key not in d:
        raise MetadataError(f"metadata version {version} lacks the key '{key}'")
    return d[key]


def _int(value: object, what: str) -> int:
    if isinstance(value, dict):
        value = next(iter(value.values()), 0)
    if not isinstance(value, (int, float, str)):
        raise MetadataError(f"bad {what}: {value!r}")
    try:
        return int(value)
    except ValueError:
        raise MetadataError(f"bad {what}: {value!r}") from None


def parse_metadata(text: str, *, top_key: bool = True) -> BagMetadata:
    """Parse metadata.yaml (any version 1-9) or a `serialized_metadata` string."""
    try:
        doc = load(text, "metadata")
    except YamlInputError as e:
        raise MetadataError(str(e)) from None
    if top_key:
        if not isinstance(doc, dict) or "rosbag2_bagfile_information" not in doc:
            raise MetadataError("metadata lacks 'rosbag2_bagfile_information'")
        doc = doc["rosbag2_bagfile_information"]
    if not isinstance(doc, dict):
        raise MetadataError("metadata is not a mapping")
    version = _int(doc.get("version", 1), "version")
    if version > METADATA_VERSION:
        raise MetadataError(
            f"metadata version {version} is newer than this reader (up to {METADATA_VERSION})"
        )
    topics = []
    for entry in _require(doc, "topics_with_message_count", version) or []:
        if not isinstance(entry, dict) or not isinstance(entry.get("topic_metadata"), dict):
            raise MetadataError(f"bad topic entry: {entry!r}")
        t = entry["topic_metadata"]
        qos = parse_qos_list(t.get("offered_qos_profiles")) if version >= 4 else []
        topics.append(
            TopicInformation(
                TopicMetadata(
                    name=str(_require(t, "name", version)),
                    type=str(_require(t, "type", version)),
                    serialization_format=str(t.get("serialization_format", "cdr")),
                    offered_qos_profiles=qos,
                    type_description_hash=str(t.get("type_description_hash") or ""),
                ),
                _int(entry.get("message_count", 0), "message_count"),
            )
        )
    files = []
    for f in doc.get("files") or []:
        if not isinstance(f, dict):
            raise MetadataError(f"bad file entry: {f!r}")
        files.append(
            FileInformation(
                path=str(_require(f, "path", version)),
                starting_time=_int(f.get("starting_time", EMPTY_STARTING_TIME), "starting_time"),
                duration=_int(f.get("duration", 0), "duration"),
                message_count=_int(f.get("message_count", 0), "message_count"),
            )
        )
    custom = doc.get("custom_data")
    return BagMetadata(
        version=version,
        storage_identifier=str(doc.get("storage_identifier") or ""),
        duration=_int(_require(doc, "duration", version), "duration"),
        starting_time=_int(_require(doc, "starting_time", version), "starting_time"),
        message_count=_int(_require(doc, "message_count", version), "message_count"),
        topics_with_message_count=topics,
        compression_format=str(doc.get("compression_format") or ""),
        compression_mode=str(doc.get("compression_mode") or ""),
        relative_file_paths=[str(p) for p in doc.get("relative_file_paths") or []],
        files=files,
        custom_data={str(k): str(v) for k, v in custom.items()}
        if isinstance(custom, dict)
        else None,
        ros_distro=str(doc.get("ros_distro") or ""),
    )


# a rosbag2 metadata.yaml of thousands of topics and files stays far below this
_METADATA_LIMIT = 16 * 1024 * 1024


def read_metadata_file(path: str | os.PathLike[str]) -> BagMetadata:
    """Parse a metadata.yaml file (MetadataError when unreadable or malformed)."""
    try:
        text = read_text_bounded(path, "bag metadata", _METADATA_LIMIT)
    except ReadRefused as e:
        raise MetadataError(f"cannot read '{path}': {e.reason}") from None
    return parse_metadata(text)


def write_metadata_file(directory: str | os.PathLike[str], m: BagMetadata) -> None:
    """Write metadata.yaml atomically (a temp file renamed over it), so a crash mid-write
    never leaves half a file."""

    # a randomly named temporary file, renamed over the old one: never through a symlink
    replace_file(Path(directory) / METADATA_FILENAME, dump_metadata(m))
