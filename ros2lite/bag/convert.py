"""`bag convert`: rewrite one or more bags into new ones, filtered and re-split.

rosbag2 describes each output in a YAML file (`output_bags:` — a list of storage options and
record options per bag). Every input is read once, all inputs merged in log-time order, and each
message goes to every output whose selection takes its topic, through the same rule the recorder
uses (:meth:`RecordOptions.selects`). Messages stay CDR bytes; topics keep their type, type hash,
recorded QoS and the definition the input bag carries.
"""

from __future__ import annotations

import heapq
import math
import os
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import TypeVar

from ros2lite.bag.errors import BagError
from ros2lite.bag.metadata import BagMetadata
from ros2lite.bag.reader import Reader
from ros2lite.bag.recorder import RecordOptions
from ros2lite.bag.writer import Writer
from ros2lite.service_introspection import event_topic
from ros2lite.util.files import ReadRefused, read_text_bounded
from ros2lite.util.safe_yaml import YamlInputError, load

__all__ = ["OutputBag", "convert", "parse_output_options", "read_output_options"]

# keys of rosbag2's StorageOptions/RecordOptions that decide nothing in a rewrite (they tune
# live recording: caches, threads, discovery, keyboard): accepted and not used
_LIVE_ONLY = {
    "max_cache_size",
    "snapshot_mode",
    "compression_queue_size",
    "compression_threads",
    "compression_threads_priority",
    "topic_polling_interval",
    "is_discovery_disabled",
    "include_unpublished_topics",
    "ignore_leaf_topics",
    "start_paused",
    "use_sim_time",
    "disable_keyboard_controls",
    "node_prefix",
    "topic_qos_profile_overrides",
}
_STRING_LISTS = (
    "topics",
    "topic_types",
    "services",
    "exclude_topics",
    "exclude_topic_types",
    "exclude_services",
    "exclude_service_events",
)
_FLAGS = ("all", "all_topics", "all_services", "include_hidden_topics")
_STRINGS = (
    "storage_id",
    "storage_preset_profile",
    "storage_config_uri",
    "regex",
    "exclude_regex",
    "rmw_serialization_format",
    "compression_mode",
    "compression_format",
)
_INTS = ("max_bagfile_size", "max_bagfile_duration", "start_time_ns", "end_time_ns")
_KNOWN = {"uri", "custom_data", *_LIVE_ONLY, *_STRING_LISTS, *_FLAGS, *_STRINGS, *_INTS}


@dataclass
class OutputBag:
    """One entry of `output_bags`: where to write, how to store it, what to take."""

    uri: str
    record: RecordOptions = field(default_factory=RecordOptions)
    storage_id: str = "mcap"
    storage_preset_profile: str | None = None
    compression: str = "none"  # chunk compression of the MCAP files
    max_bagfile_size: int = 0  # bytes
    max_bagfile_duration: int = 0  # seconds
    start_time_ns: int = -1  # only messages at or after (-1: from the start)
    end_time_ns: int = -1  # only messages at or before (-1: to the end)
    custom_data: dict[str, str] = field(default_factory=dict)

    def takes(self, topic: str, type_name: str) -> bool:
        """Whether this output records `topic`."""
        return self.record.selects(topic, type_name)


_T = TypeVar('_T')


def _field(entry: dict[str, object], key: str, kind: type[_T], where: str) -> _T | None:
    value = entry.get(key)
    if value is None:
        return None
    if (kind is int and isinstance(value, bool)) or not isinstance(value, kind):
        kinds = {int: "an integer", str: "a string", list: "a list"}
        raise BagError(f"{where}: '{key}' must be {kinds.get(kind, kind.__name__)}")
    return value


def _absolute(names: Iterable[str]) -> list[str]:
    """Each name as given and, when relative, fully qualified: recorders write `/chatter`,
    while rosbag2's own test bags hold names such as `a_empty`."""
    out = []
    for n in names:
        out.append(n)
        if not n.startswith("/"):
            out.append("/" + n)
    return out


def _entry(entry: object, index: int) -> OutputBag:
    where = f"output_bags[{index}]"
    if not isinstance(entry, dict):
        raise BagError(f"{where} must be a mapping of options")
    unknown = sorted(str(k) for k in entry if k not in _KNOWN)
    if unknown:
        raise BagError(f"{where}: unknown option(s) {', '.join(unknown)}")
    uri = _field(entry, "uri", str, where)
    if not uri:
        raise BagError(f"{where}: 'uri' (the output bag's directory) is required")
    lists: dict[str, list[str]] = {}
    for key in _STRING_LISTS:
        value = _field(entry, key, list, where) or []
        if not all(isinstance(v, str) for v in value):
            raise BagError(f"{where}: '{key}' must be a list of names")
        lists[key] = value
    flags = {}
    for key in _FLAGS:
        value = entry.get(key, False)
        if not isinstance(value, bool):
            raise BagError(f"{where}: '{key}' must be true or false")
        flags[key] = value
    text = {key: _field(entry, key, str, where) or "" for key in _STRINGS}
    ints = {key: _field(entry, key, int, where) for key in _INTS}
    if text["rmw_serialization_format"] not in ("", "cdr"):
        raise BagError(
            f"{where}: serialization format '{text['rmw_serialization_format']}' is not "
            f"supported (messages stay CDR)"
        )
    if text["storage_config_uri"]:
        raise BagError(f"{where}: 'storage_config_uri' is not supported (use a preset profile)")
    mode = text["compression_mode"].lower()
    if mode not in ("", "none"):
        raise BagError(
            f"{where}: compression mode '{text['compression_mode']}' is not supported for MCAP; "
            f"give compression_format alone (chunk compression)"
        )
    custom = entry.get("custom_data") or {}
    if not isinstance(custom, dict) or not all(
        isinstance(k, str) and isinstance(v, str) for k, v in custom.items()
    ):
        raise BagError(f"{where}: 'custom_data' must map strings to strings")
    for key in ("regex", "exclude_regex"):
        if text[key]:
            try:
                re.compile(text[key])
            except re.error as e:
                raise BagError(f"{where}: '{key}' is not a regular expression: {e}") from None

    record = RecordOptions(
        topics=_absolute(lists["topics"]) + [event_topic(s) for s in _absolute(lists["services"])],
        all_topics=flags["all"] or flags["all_topics"],
        all_services=flags["all"] or flags["all_services"],
        regex=text["regex"] or None,
        exclude_regex=text["exclude_regex"] or None,
        exclude_topics=_absolute(lists["exclude_topics"])
        + [event_topic(s) for s in _absolute(lists["exclude_services"])]
        + _absolute(lists["exclude_service_events"]),
        topic_types=lists["topic_types"],
        exclude_topic_types=lists["exclude_topic_types"],
        include_hidden_topics=flags["include_hidden_topics"],
    )
    duration = ints["max_bagfile_duration"] or 0
    size = ints["max_bagfile_size"] or 0
    if duration < 0 or size < 0:
        raise BagError(f"{where}: split limits must not be negative")
    return OutputBag(
        uri=uri,
        record=record,
        storage_id=text["storage_id"] or "mcap",
        storage_preset_profile=text["storage_preset_profile"] or None,
        compression=text["compression_format"] or "none",
        max_bagfile_size=size,
        max_bagfile_duration=duration,
        start_time_ns=-1 if ints["start_time_ns"] is None else ints["start_time_ns"],
        end_time_ns=-1 if ints["end_time_ns"] is None else ints["end_time_ns"],
        custom_data=dict(custom),
    )


def parse_output_options(text: str) -> list[OutputBag]:
    """The `--output-options` YAML: `output_bags:` and one mapping of options per bag."""
    try:
        doc = load(text, "output options")
    except YamlInputError as e:
        raise BagError(str(e)) from None
    if not isinstance(doc, dict) or "output_bags" not in doc:
        raise BagError("The output options must be a mapping with an 'output_bags' list")
    bags = doc["output_bags"]
    if not isinstance(bags, list) or not bags:
        raise BagError("'output_bags' must be a non-empty list")
    outputs = [_entry(e, i) for i, e in enumerate(bags)]
    uris = [os.path.normpath(o.uri) for o in outputs]
    if len(set(uris)) != len(uris):
        raise BagError("Two output bags have the same uri")
    return outputs


def read_output_options(path: str | os.PathLike[str]) -> list[OutputBag]:
    """The output options file at `path` (see :func:`parse_output_options`)."""
    try:
        text = read_text_bounded(path, "an output options file")
    except ReadRefused as e:
        raise BagError(f"Cannot read '{path}': {e.reason}") from None
    return parse_output_options(text)


def convert(
    inputs: Sequence[tuple[str | os.PathLike[str], str | None]], outputs: Sequence[OutputBag]
) -> list[BagMetadata]:
    """Rewrite the bags `inputs` ((uri, storage id or None)) into `outputs`; returns each
    output's metadata. A failure leaves no half-written output behind."""
    if not inputs:
        raise BagError("No input bag")
    readers: list[Reader] = []
    writers: list[Writer] = []
    opened: list[Writer] = []
    try:
        for uri, storage_id in inputs:
            readers.append(Reader(uri, storage_id))
        for out in outputs:
            writers.append(
                Writer(
                    out.uri,
                    storage_id=out.storage_id,
                    compression=out.compression,
                    preset=out.storage_preset_profile,
                    max_bag_size=out.max_bagfile_size,
                    max_bag_duration=float(out.max_bagfile_duration),
                    custom_data=out.custom_data or None,
                )
            )
        for w in writers:
            w.open()
            opened.append(w)
        _copy(readers, outputs, writers)
        for w in writers:
            w.close()
        return [w.metadata() for w in writers]
    except BaseException:
        # a part of a conversion would pass for the whole of it
        for w in opened:
            w.discard()
        raise
    finally:
        for r in readers:
            r.close()


def _copy(readers: list[Reader], outputs: Sequence[OutputBag], writers: list[Writer]) -> None:
    # (input index, topic) → where it goes: writer, its topic id, the output's time window
    routes: dict[tuple[int, str], list[tuple[Writer, int, int, float]]] = {}
    types: dict[str, str] = {}  # topic → its type across the inputs
    for i, reader in enumerate(readers):
        for meta in reader.topics:
            targets = []
            for out, writer in zip(outputs, writers, strict=True):
                if not out.takes(meta.name, meta.type):
                    continue
                known = types.setdefault(meta.name, meta.type)
                if known != meta.type:
                    raise BagError(
                        f"Topic '{meta.name}' has type {known} in one input bag and "
                        f"{meta.type} in another"
                    )
                tid = writer.create_topic(
                    meta.name,
                    meta.type,
                    offered_qos_profiles=meta.offered_qos_profiles,
                    type_description_hash=meta.type_description_hash,
                    definition=reader.definition(meta.type),
                    serialization_format=meta.serialization_format,
                )
                end = math.inf if out.end_time_ns < 0 else out.end_time_ns
                targets.append((writer, tid, out.start_time_ns, end))
            if targets:
                routes[(i, meta.name)] = targets
    wanted = [{t for (j, t) in routes if j == i} for i in range(len(readers))]

    def stream(i: int) -> Iterable[tuple[int, int, str, bytes, int]]:
        for topic, data, log_time, publish_time in readers[i].raw_messages(wanted[i]):
            yield log_time, i, topic, data, publish_time

    for log_time, i, topic, data, publish_time in heapq.merge(
        *(stream(i) for i in range(len(readers)) if wanted[i]), key=lambda m: m[0]
    ):
        for writer, tid, start, end in routes[(i, topic)]:
            if start <= log_time <= end:
                writer.write_raw(tid, data, log_time, publish_time)
