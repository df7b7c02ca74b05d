"""Every bag rosbag2 itself wrote (tests/bag/data, copied from its test resources) reads with
the counts its metadata states, and its messages decode, unknown types included."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from ros2lite.bag import Reader
from ros2lite.bag.metadata import read_metadata_file
from ros2lite.bag.reindex import reindex

DATA = Path(__file__).parent / "data"
WITH_YAML = sorted(p.parent for p in DATA.glob("*/*/metadata.yaml"))


@pytest.mark.parametrize("bag", WITH_YAML, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_counts_match_metadata_and_messages(bag: Path) -> None:
    expected = read_metadata_file(bag / "metadata.yaml")
    with Reader(bag) as reader:
        seen: dict[str, int] = {}
        times = []
        for topic, _msg, t in reader.messages(raw=True):
            seen[topic] = seen.get(topic, 0) + 1
            times.append(t)
        assert times == sorted(times)  # log-time order across files
        for info in expected.topics_with_message_count:
            assert seen.get(info.topic_metadata.name, 0) == info.message_count
        assert sum(seen.values()) == expected.message_count


@pytest.mark.parametrize("bag", WITH_YAML, ids=lambda p: f"{p.parent.name}/{p.name}")
def test_every_cdr_message_decodes(bag: Path) -> None:
    with Reader(bag) as reader:
        cdr = {t.name for t in reader.topics if t.serialization_format == "cdr"}
        for topic, msg, _t in reader:
            if topic in cdr:
                assert not isinstance(msg, bytes), (topic, msg)
            else:
                assert isinstance(msg, bytes)  # wrong_rmw_test: not CDR, left as bytes


def test_types_this_machine_lacks_decode_from_the_bag() -> None:
    from ros2lite.interfaces import InterfaceError, get_interface

    with pytest.raises(InterfaceError):
        get_interface("test_msgs/msg/Arrays")
    with Reader(DATA / "mcap" / "cdr_test") as reader:
        arrays = [m for topic, m, _ in reader if topic == "/array_topic"]
    assert len(arrays) == 4
    assert type(arrays[0]).__name__ == "Arrays"
    # the oracle: rosbags decodes the same bytes from the same definitions
    from rosbags.highlevel import AnyReader

    with AnyReader([DATA / "mcap" / "cdr_test"]) as oracle:
        expected = [
            oracle.deserialize(raw, c.msgtype)
            for c, _, raw in oracle.messages()
            if c.topic == "/array_topic"
        ]
    for ours, theirs in zip(arrays, expected, strict=True):
        assert list(ours.string_values) == list(theirs.string_values)
        assert list(ours.bool_values) == [bool(b) for b in theirs.bool_values]
        assert list(ours.int32_values) == [int(v) for v in theirs.int32_values]
        assert list(ours.float64_values) == [float(v) for v in theirs.float64_values]
        assert ours.basic_types_values[0].int64_value == theirs.basic_types_values[0].int64_value


def test_service_events_and_old_srv_text() -> None:
    with Reader(DATA / "mcap" / "bag_with_topics_and_service_events") as reader:
        events = [m for topic, m, _ in reader if topic.endswith("/_service_event")]
    assert len(events) == 8
    assert {type(e).__name__ for e in events} == {"BasicTypes_Event"}
    assert all(len(e.request) + len(e.response) == 1 for e in events)


def test_bare_files_and_directories_without_metadata() -> None:
    with Reader(DATA / "mcap" / "multiple_files") as reader:
        assert [f.name for f in reader.files] == [
            "multiple_files_0.mcap",
            "multiple_files_1.mcap",
            "multiple_files_2.mcap",
        ]
        assert reader.message_count == 1324 + 1324 + 529
        assert sum(1 for _ in reader) == reader.message_count
    with Reader(DATA / "mcap" / "talker" / "talker.mcap") as reader:
        assert reader.message_count == 20
        strings = [m.data for topic, m, _ in reader if topic == "/topic"]
        assert strings[0] == "Hello, world! 0" and len(strings) == 10
    with Reader(DATA / "sqlite3" / "talker" / "talker.db3") as reader:
        assert reader.message_count == 20
        assert reader.metadata.storage_identifier == "sqlite3"


def test_publish_time_and_time_filter() -> None:
    with Reader(DATA / "mcap" / "test_bag_for_seek") as reader:
        stamps = [t for _, _, t in reader]
        assert len(stamps) == 5
        middle = list(reader.messages(start=stamps[1], stop=stamps[3]))
        assert [t for _, _, t in middle] == stamps[1:3]
        raw = list(reader.raw_messages())
        assert all(len(r) == 4 and isinstance(r[1], bytes) for r in raw)


def test_reindex_rebuilds_metadata_from_files(tmp_path: Path) -> None:
    bag = tmp_path / "multiple_files"
    shutil.copytree(DATA / "mcap" / "multiple_files", bag)
    meta = reindex(bag)
    written = read_metadata_file(bag / "metadata.yaml")
    assert written.version == 9 and written.message_count == meta.message_count == 3177
    assert [f.message_count for f in written.files] == [1324, 1324, 529]
    assert written.relative_file_paths == [f.path for f in written.files]
    assert written.starting_time == 1616653333034080451
    assert written.duration == 1616653339386193357 - 1616653333034080451
    assert written.topics_with_message_count[0].topic_metadata.type == "std_msgs/msg/String"
