"""`bag convert` in the library: rosbag2's own rewrite test bags merged and filtered, a
sqlite3 bag rewritten to MCAP byte for byte, time windows, splits, and refusals that leave
nothing behind."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite.bag import Reader, Writer
from ros2lite.bag.convert import OutputBag, convert, parse_output_options
from ros2lite.bag.errors import BagError
from ros2lite.bag.recorder import RecordOptions
from ros2lite.interfaces import get_interface

DATA = Path(__file__).parent / "data"
A, B = DATA / "mcap" / "convert_a", DATA / "mcap" / "convert_b"
String = get_interface("std_msgs/msg/String")


def counts(path: Path) -> dict[str, int]:
    with Reader(path) as r:
        return {
            t.topic_metadata.name: t.message_count for t in r.metadata.topics_with_message_count
        }


def raw(path: Path) -> list[tuple[str, bytes, int]]:
    with Reader(path) as r:
        return [(t, d, lt) for t, d, lt, _ in r.raw_messages()]


def test_rosbag2_rewrite_bags_merge_and_filter(tmp_path: Path) -> None:
    outputs = parse_output_options(
        f"""
output_bags:
- uri: {tmp_path / "merged"}
  all_topics: true
- uri: {tmp_path / "only_a"}
  topics: [a_empty]
  storage_preset_profile: zstd_fast
- uri: {tmp_path / "no_strings"}
  all: true
  exclude_topic_types: [test_msgs/msg/Strings]
  max_bagfile_duration: 0
"""
    )
    convert([(A, None), (B, "mcap")], outputs)
    # the figures rosbag2's own rewrite test expects of these two bags
    assert counts(tmp_path / "merged") == {"a_empty": 125, "b_basictypes": 50, "c_strings": 50}
    assert counts(tmp_path / "only_a") == {"a_empty": 125}
    assert counts(tmp_path / "no_strings") == {"a_empty": 125, "b_basictypes": 50}
    merged = raw(tmp_path / "merged")
    assert [m[2] for m in merged] == sorted(m[2] for m in merged)  # one time order
    # every message kept as it was, definitions carried over (rosbags decodes test_msgs)
    assert sorted(merged) == sorted(raw(A) + raw(B))
    from rosbags.highlevel import AnyReader

    with AnyReader([tmp_path / "merged"]) as reader:
        decoded = [reader.deserialize(d, c.msgtype) for c, _t, d in reader.messages()]
    assert len(decoded) == 225


def test_sqlite3_to_mcap_window_and_split(tmp_path: Path) -> None:
    src = DATA / "sqlite3" / "talker"
    messages = raw(src)
    first, last = messages[0][2], messages[-1][2]
    middle = messages[len(messages) // 2][2]
    out = OutputBag(
        uri=str(tmp_path / "out"),
        record=RecordOptions(all_topics=True, include_hidden_topics=True),
        start_time_ns=middle,
        end_time_ns=last,
    )
    convert([(src, None)], [out])
    assert raw(tmp_path / "out") == [m for m in messages if middle <= m[2] <= last]
    assert first < middle

    # a bag split by size while converting: several files, all messages in order
    big = tmp_path / "big"
    with Writer(big) as bag:
        for i in range(400):
            bag.write("/chatter", String(data="x" * 200 + str(i)), 1_000 + i)
    split = OutputBag(
        uri=str(tmp_path / "split"),
        record=RecordOptions(topics=["/chatter"]),
        max_bagfile_size=20_000,
    )
    convert([(big, None)], [split])
    with Reader(tmp_path / "split") as r:
        assert len(r.files) > 1
    assert raw(tmp_path / "split") == raw(big)


def test_refusals_name_the_problem_and_leave_nothing(tmp_path: Path) -> None:
    (tmp_path / "taken").mkdir()
    outputs = parse_output_options(
        f"output_bags:\n- uri: {tmp_path / 'fresh'}\n  all_topics: true\n"
        f"- uri: {tmp_path / 'taken'}\n  all_topics: true\n"
    )
    with pytest.raises(BagError, match="already exists"):
        convert([(A, None)], outputs)
    assert not (tmp_path / "fresh").exists()  # the first output was removed again
    assert (tmp_path / "taken").is_dir()  # and what was there before is untouched

    # one topic, two types across the inputs
    with Writer(tmp_path / "other") as bag:
        bag.write("a_empty", String(data="not empty"), 5)
    out = [OutputBag(uri=str(tmp_path / "clash"), record=RecordOptions(all_topics=True))]
    with pytest.raises(BagError, match=r"a_empty.*test_msgs/msg/Empty.*std_msgs/msg/String"):
        convert([(A, None), (tmp_path / "other", None)], out)
    assert not (tmp_path / "clash").exists()

    for text, message in [
        ("output_bags: []", "non-empty list"),
        ("- uri: x", "mapping with an 'output_bags' list"),
        ("output_bags:\n- uri: x\n  topicz: [a]", "unknown option.*topicz"),
        ("output_bags:\n- all_topics: true", "'uri'.*required"),
        ("output_bags:\n- uri: x\n  topics: /a", "'topics' must be a list"),
        ("output_bags:\n- uri: x\n  max_bagfile_size: '10'", "must be an integer"),
        ("output_bags:\n- uri: x\n  regex: '('", "not a regular expression"),
        ("output_bags:\n- uri: x\n  compression_mode: message", "not supported for MCAP"),
        ("output_bags:\n- uri: x\n- uri: ./x", "same uri"),
        ("output_bags: [", "output options"),
    ]:
        with pytest.raises(BagError, match=message):
            parse_output_options(text)
    bad = parse_output_options("output_bags:\n- uri: y\n  storage_id: sqlite3")
    with pytest.raises(BagError, match=r"sqlite3.*not supported"):
        convert([(A, None)], bad)
