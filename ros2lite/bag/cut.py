"""`bag cut` and `bag filter`: a new bag holding part of another, by time range and by topic.

MCAP files with a summary are spliced (`storage/mcap/splice`): the chunks wholly inside the cut
are copied as bytes, only the edge chunks are inflated and re-encoded, so the cost follows the
size of what is kept. Other inputs (sqlite3, a file without a summary) are read message by
message and written anew, as `bag convert` does. Topics keep their type, hash, QoS and
definition; the metadata.yaml written counts what the new bag holds.
"""

from __future__ import annotations

import contextlib
import datetime
import os
import re
from collections.abc import Iterable
from dataclasses import dataclass, field
from decimal import Decimal, InvalidOperation
from pathlib import Path

from ros2lite.bag.errors import BagError
from ros2lite.bag.metadata import (
    BagMetadata,
    FileInformation,
    TopicInformation,
    dump_metadata,
    write_metadata_file,
)
from ros2lite.bag.reader import Reader
from ros2lite.bag.storage.mcap.splice import SpliceResult, splice
from ros2lite.bag.storage.mcap.write import library_name
from ros2lite.bag.writer import Writer

__all__ = ["CutResult", "cut", "parse_time"]

_CLOCK = re.compile(r"^(?:(\d+):)?(\d+):(\d+(?:\.\d*)?)$")
# a plain number this large is a time since the epoch, not an offset into the bag (no bag
# lasts 30 years): seconds from 1e9 up, nanoseconds from 1e18 up
_EPOCH_SECONDS = 10**9
_EPOCH_NANOSECONDS = 10**18


def _ns(seconds: Decimal) -> int:
    """Seconds, exactly as written (`bag echo` prints nine decimals), to whole nanoseconds."""
    return int((seconds * 10**9).to_integral_value())


def parse_time(text: str, bag_start: int) -> int:
    """A time given on the command line as ns since the epoch: seconds from the bag's start
    (`90`, `12.5`), a duration from the start (`1:30`, `1:02:03.5`), or an absolute time
    (seconds or nanoseconds since the epoch, or an ISO 8601 date and time, UTC unless it
    says otherwise). Decimal, not float: `1700000000.123456789` keeps its last digit."""
    value = text.strip()
    m = _CLOCK.match(value)
    if m is not None:
        hours, minutes, seconds = m.groups()
        if (int(minutes) >= 60 and hours is not None) or Decimal(seconds) >= 60:
            raise BagError(f"Bad time '{text}': minutes and seconds go up to 59")
        offset = int(hours or 0) * 3600 + int(minutes) * 60 + Decimal(seconds)
        return bag_start + _ns(offset)
    try:
        number: Decimal | None = Decimal(value)
    except InvalidOperation:
        number = None
    if number is not None:
        if not number.is_finite() or number.adjusted() > 20:  # no time has 21 digits
            raise BagError(f"Bad time '{text}'")
        if number >= _EPOCH_NANOSECONDS:
            return int(number.to_integral_value())
        if number >= _EPOCH_SECONDS:
            return _ns(number)
        if number < 0:
            raise BagError(f"Bad time '{text}': an offset from the start is not negative")
        return bag_start + _ns(number)
    try:
        when = datetime.datetime.fromisoformat(value)
    except ValueError:
        raise BagError(
            f"Bad time '{text}': give seconds from the start (90), a duration (1:30) or an "
            "absolute time (seconds since the epoch, or 2024-05-01T12:00:00)"
        ) from None
    if when.tzinfo is None:
        when = when.replace(tzinfo=datetime.timezone.utc)
    delta = when - datetime.datetime(1970, 1, 1, tzinfo=datetime.timezone.utc)
    return (delta.days * 86400 + delta.seconds) * 1_000_000_000 + delta.microseconds * 1000


@dataclass
class CutResult:
    """The new bag's metadata and how it was made."""

    metadata: BagMetadata
    chunks_copied: int = 0
    chunks_rewritten: int = 0
    spliced: bool = True  # False: read and written message by message
    problems: list[str] = field(default_factory=list)


def _names(names: Iterable[str] | None) -> set[str] | None:
    if names is None:
        return None
    out = set()
    for n in names:
        out.add(n)
        out.add(n if n.startswith("/") else "/" + n)
    return out


def cut(
    bag: str | os.PathLike[str],
    output: str | os.PathLike[str],
    *,
    start: int | None = None,
    end: int | None = None,
    topics: Iterable[str] | None = None,
    exclude: Iterable[str] | None = None,
) -> CutResult:
    """Write to the new bag `output` the messages of `bag` logged from `start` to `end` (ns
    since the epoch, both included; None: the bag's own start or end) on the chosen topics
    (`topics`: only these; `exclude`: not these)."""
    wanted, dropped = _names(topics), _names(exclude) or set()
    out = Path(output)
    if not out.name:
        raise BagError(f"Invalid bag path '{output}'")
    with Reader(bag) as reader:
        chosen = [
            t
            for t in reader.topics
            if (wanted is None or t.name in wanted) and t.name not in dropped
        ]
        if topics is not None:
            have = {t.name for t in reader.topics}
            missing = [n for n in topics if n not in have and "/" + n not in have]
            if missing:
                raise BagError(f"The bag has no topic {', '.join(missing)}")
        if start is not None and end is not None and end < start:
            raise BagError("The end of the cut is before its start")
        if os.path.lexists(out):
            raise BagError(f"Output folder '{out}' already exists.")
        stop = None if end is None else end + 1
        names = {t.name for t in chosen}
        mcap = all(f.name.endswith(".mcap") for f in reader.files)
        if mcap:
            try:
                return _splice_bag(reader, out, names, start, stop)
            except _NotSpliceable:
                pass
        return _rewrite(reader, out, names, start, end)


class _NotSpliceable(Exception):
    """A file of the bag cannot be spliced (no summary): the bag is rewritten instead."""


def _splice_bag(
    reader: Reader, out: Path, names: set[str], start: int | None, stop: int | None
) -> CutResult:

    source = reader.metadata
    for f in reader.files:
        summary = reader.summary(f)
        if not summary.complete:
            raise _NotSpliceable
    sources = []
    for f in reader.files:
        s = reader.summary(f)
        if s.start is None or s.end is None:
            continue
        if (stop is not None and s.start >= stop) or (start is not None and s.end < start):
            continue
        if not any(s.counts.get(n, 0) for n in names):
            continue
        sources.append(f)
    if not sources:
        sources = reader.files[:1]
    try:
        out.mkdir(parents=True)
    except OSError as e:
        raise BagError(f"Cannot create '{out}': {e.strerror or e}") from None
    result = CutResult(_metadata(source, [], {}))
    files: list[FileInformation] = []
    counts: dict[str, int] = dict.fromkeys(names, 0)
    try:
        for i, f in enumerate(sources):
            name = f"{out.name}_{i}.mcap"

            def record(r: SpliceResult, name: str = name) -> dict[str, str]:
                info = _file_info(name, r)
                so_far = {n: counts[n] + r.counts.get(n, 0) for n in counts}
                meta = _metadata(source, [*files, info], so_far)
                return {"serialized_metadata": dump_metadata(meta, top_key=False)}

            try:
                r = splice(
                    str(f),
                    str(out / name),
                    keep=lambda c: c.topic in names,
                    start=start,
                    stop=stop,
                    metadata=record,
                    library=library_name(),
                )
            except BagError:
                if i == 0:
                    raise _NotSpliceable from None
                raise
            files.append(_file_info(name, r))
            for n, c in r.counts.items():
                counts[n] = counts.get(n, 0) + c
            result.chunks_copied += r.chunks_copied
            result.chunks_rewritten += r.chunks_rewritten
            result.problems.extend(f"'{f}': {p}" for p in r.problems)
        result.metadata = _metadata(source, files, counts)
        write_metadata_file(out, result.metadata)
    except BaseException:
        _remove(out)
        raise
    return result


def _file_info(name: str, r: SpliceResult) -> FileInformation:
    if r.start is None or r.end is None:
        return FileInformation(name)
    return FileInformation(name, r.start, r.end - r.start, r.message_count)


def _metadata(
    source: BagMetadata, files: list[FileInformation], counts: dict[str, int]
) -> BagMetadata:
    """The new bag's metadata: the source's topics (type, QoS, hash) that were kept, with the
    counts and times of what was written."""
    with_messages = [f for f in files if f.message_count]
    start = min((f.starting_time for f in with_messages), default=None)
    end = max((f.starting_time + f.duration for f in with_messages), default=None)
    m = BagMetadata(
        storage_identifier="mcap",
        duration=0 if start is None or end is None else end - start,
        message_count=sum(f.message_count for f in files),
        topics_with_message_count=[
            TopicInformation(t.topic_metadata, counts[t.topic_metadata.name])
            for t in source.topics_with_message_count
            if t.topic_metadata.name in counts
        ],
        relative_file_paths=[f.path for f in files],
        files=list(files),
        custom_data=source.custom_data,
        ros_distro=source.ros_distro or BagMetadata().ros_distro,
    )
    if start is not None:
        m.starting_time = start
    return m


def _remove(out: Path) -> None:
    for p in out.iterdir() if out.is_dir() else ():
        with contextlib.suppress(OSError):
            p.unlink()
    with contextlib.suppress(OSError):
        out.rmdir()


def _rewrite(
    reader: Reader, out: Path, names: set[str], start: int | None, end: int | None
) -> CutResult:
    """The bag read message by message and written anew (inputs that cannot be spliced)."""
    writer = Writer(out, custom_data=reader.metadata.custom_data)
    writer.open()
    try:
        ids = {}
        for t in reader.topics:
            if t.name in names:
                ids[t.name] = writer.create_topic(
                    t.name,
                    t.type,
                    offered_qos_profiles=t.offered_qos_profiles,
                    type_description_hash=t.type_description_hash,
                    definition=reader.definition(t.type),
                    serialization_format=t.serialization_format,
                )
        stop = None if end is None else end + 1
        for topic, data, log_time, publish_time in reader.raw_messages(names, start, stop):
            writer.write_raw(ids[topic], data, log_time, publish_time)
        writer.close()
    except BaseException:
        writer.discard()
        raise
    return CutResult(writer.metadata(), spliced=False)
