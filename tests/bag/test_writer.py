"""Bags we write open in the oracles (rosbags, mcap-ros2-support) and carry rosbag2's layout:
schemas with the full definition, channel QoS and hash, `rosbag2` records, splits,
compression; truncated files are recovered; bad paths and files give one clear error."""

from __future__ import annotations

import os
import time
from pathlib import Path

import pytest
from mcap.reader import make_reader

from ros2lite.bag import BagError, Reader, Writer
from ros2lite.bag.metadata import (
    dump_metadata,
    dump_qos_list,
    parse_qos_list,
    read_metadata_file,
)
from ros2lite.bag.reindex import reindex
from ros2lite.interfaces import definition_text, get_interface, type_hash
from ros2lite.qos import (
    DURATION_INFINITE,
    DurabilityPolicy,
    HistoryPolicy,
    LivelinessPolicy,
    QoSProfile,
    ReliabilityPolicy,
)

String = get_interface("std_msgs/msg/String")
Imu = get_interface("sensor_msgs/msg/Imu")
LATCHED = QoSProfile(durability=DurabilityPolicy.TRANSIENT_LOCAL, depth=1)


def write_sample(path: Path, **kw: object) -> None:
    with Writer(path, **kw) as bag:  # type: ignore[arg-type]
        bag.create_topic("/imu", "sensor_msgs/msg/Imu", offered_qos_profiles=[LATCHED])
        for i in range(50):
            imu = Imu()
            imu.header.frame_id = f"imu{i}"
            imu.linear_acceleration.z = 9.81 + i
            bag.write(
                "/imu",
                imu,
                1_700_000_000_000_000_000 + i * 1_000_000,
                publish_time=1_700_000_000_000_000_000 + i * 1_000_000 - 5,
            )
            bag.write(
                "/chatter",
                String(data=f"hello {i}"),
                1_700_000_000_000_000_000 + i * 1_000_000 + 500,
            )


def test_rosbags_reads_our_bag_without_hash_mismatch(tmp_path: Path) -> None:
    from rosbags.highlevel import AnyReader

    write_sample(tmp_path / "bag")
    with AnyReader([tmp_path / "bag"]) as reader:
        by_topic: dict[str, list[object]] = {}
        for conn, _t, raw in reader.messages():
            by_topic.setdefault(conn.topic, []).append(reader.deserialize(raw, conn.msgtype))
        assert {c.topic: c.msgtype for c in reader.connections} == {
            "/imu": "sensor_msgs/msg/Imu",
            "/chatter": "std_msgs/msg/String",
        }
    assert [m.data for m in by_topic["/chatter"]] == [f"hello {i}" for i in range(50)]
    assert [m.header.frame_id for m in by_topic["/imu"]][-1] == "imu49"
    assert by_topic["/imu"][3].linear_acceleration.z == pytest.approx(12.81)


def test_mcap_ros2_support_decodes_every_message(tmp_path: Path) -> None:
    from mcap_ros2.decoder import DecoderFactory

    write_sample(tmp_path / "bag")
    with open(tmp_path / "bag" / "bag_0.mcap", "rb") as f:
        decoded = [
            (c.topic, d)
            for _s, c, _m, d in make_reader(
                f, decoder_factories=[DecoderFactory()]
            ).iter_decoded_messages()
        ]
    assert len(decoded) == 100
    assert decoded[1][0] == "/chatter" and decoded[1][1].data == "hello 0"
    assert decoded[-2][1].header.frame_id == "imu49"


def test_file_layout_is_rosbag2s(tmp_path: Path) -> None:
    write_sample(tmp_path / "bag")
    assert sorted(os.listdir(tmp_path / "bag")) == ["bag_0.mcap", "metadata.yaml"]
    meta = read_metadata_file(tmp_path / "bag" / "metadata.yaml")
    with open(tmp_path / "bag" / "bag_0.mcap", "rb") as f:
        reader = make_reader(f)
        assert reader.get_header().profile == "ros2"
        summary = reader.get_summary()
        assert summary is not None and summary.statistics is not None
        assert summary.statistics.message_count == 100
        assert summary.chunk_indexes and all(c.message_index_offsets for c in summary.chunk_indexes)
        schemas = {s.name: s for s in summary.schemas.values()}
        assert schemas["sensor_msgs/msg/Imu"].encoding == "ros2msg"
        assert schemas["sensor_msgs/msg/Imu"].data.decode() == definition_text(
            "sensor_msgs/msg/Imu"
        )
        channels = {c.topic: c for c in summary.channels.values()}
        imu = channels["/imu"]
        assert imu.message_encoding == "cdr"
        assert imu.metadata["topic_type_hash"] == type_hash("sensor_msgs/msg/Imu")
        # the same QoS in the channel and in metadata.yaml (rosbags pairs them up by it)
        assert (
            parse_qos_list(imu.metadata["offered_qos_profiles"])
            == [LATCHED]
            == meta.topic("/imu").topic_metadata.offered_qos_profiles
        )  # type: ignore[union-attr]
        records = [m for m in reader.iter_metadata() if m.name == "rosbag2"]
        assert len(records) == 2  # one when opened, the final one at close
        assert "message_count: 100" in records[-1].metadata["serialized_metadata"]
        messages = list(reader.iter_messages())
    first = messages[0][2]
    assert (first.log_time, first.publish_time) == (
        1_700_000_000_000_000_000,
        1_700_000_000_000_000_000 - 5,
    )
    assert meta.message_count == 100 and meta.duration == 49 * 1_000_000 + 500
    assert meta.starting_time == 1_700_000_000_000_000_000


def test_metadata_yaml_matches_rosbag2_v9_layout(tmp_path: Path) -> None:
    with Writer(tmp_path / "my_bag") as bag:
        bag.create_topic(
            "/chatter",
            "std_msgs/msg/String",
            offered_qos_profiles=[
                QoSProfile(
                    reliability=ReliabilityPolicy.RELIABLE,
                    depth=0,
                    history=HistoryPolicy.UNKNOWN,
                    deadline=DURATION_INFINITE,
                    lifespan=DURATION_INFINITE,
                    liveliness=LivelinessPolicy.AUTOMATIC,
                    liveliness_lease_duration=DURATION_INFINITE,
                )
            ],
        )
        for i in range(3):
            bag.write("/chatter", String(data="x"), 1700000000000000000 + i * 1000000000)
    text = (tmp_path / "my_bag" / "metadata.yaml").read_text()
    expected = (Path(__file__).parent / "data" / "expected_v9.yaml").read_text()
    assert text == expected


def test_split_by_size_and_duration(tmp_path: Path) -> None:
    with Writer(tmp_path / "sized", max_bag_size=4096, chunk_size=1024) as bag:
        for i in range(200):
            bag.write("/chatter", String(data="x" * 50), 1000 + i)
    files = read_metadata_file(tmp_path / "sized" / "metadata.yaml").files
    assert len(files) > 2
    assert [f.path for f in files] == [f"sized_{i}.mcap" for i in range(len(files))]
    assert sum(f.message_count for f in files) == 200
    for f in files:
        with open(tmp_path / "sized" / f.path, "rb") as stream:
            reader = make_reader(stream)
            summary = reader.get_summary()
            assert summary is not None
            assert [c.topic for c in summary.channels.values()] == ["/chatter"]
            assert len([m for m in reader.iter_metadata() if m.name == "rosbag2"]) == 2
    with Writer(tmp_path / "timed", max_bag_duration=1.0) as bag:
        for i in range(10):
            bag.write("/chatter", String(data="x"), i * 300_000_000)
    timed = read_metadata_file(tmp_path / "timed" / "metadata.yaml").files
    assert [f.message_count for f in timed] == [4, 4, 2]
    with Reader(tmp_path / "timed") as reader:
        assert [t for _, _, t in reader] == [i * 300_000_000 for i in range(10)]


@pytest.mark.parametrize(
    "how", [{"compression": "zstd"}, {"preset": "zstd_small"}, {"compression": "lz4"}]
)
def test_compressed_chunks_stay_readable(tmp_path: Path, how: dict[str, str]) -> None:
    from rosbags.highlevel import AnyReader

    with Writer(tmp_path / "z", **how) as bag:  # type: ignore[arg-type]
        for i in range(300):
            bag.write("/chatter", String(data="compress me " * 20), i)
    with open(tmp_path / "z" / "z_0.mcap", "rb") as f:
        summary = make_reader(f).get_summary()
    assert summary is not None
    assert {c.compression for c in summary.chunk_indexes} == {how.get("compression", "zstd")}
    assert sum(c.compressed_size for c in summary.chunk_indexes) < 300 * 240 / 4
    meta = read_metadata_file(tmp_path / "z" / "metadata.yaml")
    assert (meta.compression_format, meta.compression_mode) == ("", "")  # chunk compression
    with AnyReader([tmp_path / "z"]) as reader:
        assert sum(1 for _ in reader.messages()) == 300


def test_killed_writer_is_recovered_up_to_the_last_chunk(tmp_path: Path) -> None:
    bag = Writer(tmp_path / "k", chunk_size=2048)
    for i in range(300):
        bag.write("/chatter", String(data=f"message {i:04d}" + "x" * 40), 1000 + i)
    bag.flush()
    path = tmp_path / "k" / "k_0.mcap"
    # what a SIGKILL leaves: complete chunks, then half a record, no summary, no yaml
    with open(path, "ab") as f:
        f.write(b"\x06\xff\xff\x00\x00\x00\x00\x00\x00partial")
    assert not (tmp_path / "k" / "metadata.yaml").exists()
    with Reader(tmp_path / "k") as reader:  # readable as it is
        assert [m.data[:12] for _, m, _ in reader] == [f"message {i:04d}" for i in range(300)]
    meta = reindex(tmp_path / "k")
    assert meta.message_count == 300
    from rosbags.highlevel import AnyReader

    with AnyReader([tmp_path / "k"]) as oracle:
        assert sum(1 for _ in oracle.messages()) == 300


def test_bad_paths_and_files_give_one_line_errors(tmp_path: Path) -> None:
    with pytest.raises(BagError, match="does not exist"):
        Reader(tmp_path / "nope")
    (tmp_path / "garbage.mcap").write_bytes(b"not an mcap file at all")
    with pytest.raises(BagError, match="not an MCAP file"):
        Reader(tmp_path / "garbage.mcap")
    (tmp_path / "garbage.db3").write_bytes(b"not sqlite either" * 100)
    with pytest.raises(BagError, match="not a readable sqlite3 bag"):
        Reader(tmp_path / "garbage.db3").metadata  # noqa: B018
    (tmp_path / "empty").mkdir()
    with pytest.raises(BagError, match="No bag files"):
        Reader(tmp_path / "empty")
    (tmp_path / "badyaml").mkdir()
    (tmp_path / "badyaml" / "metadata.yaml").write_text("rosbag2_bagfile_information: [")
    with pytest.raises(BagError, match="Bad metadata"):
        Reader(tmp_path / "badyaml")
    write_sample(tmp_path / "exists")
    with pytest.raises(BagError, match=r"Output folder .* already exists"):
        Writer(tmp_path / "exists").open()
    locked = tmp_path / "locked"
    locked.mkdir(mode=0o500)
    if os.geteuid() != 0:  # root writes anywhere
        with pytest.raises(BagError, match="Cannot create"):
            Writer(locked / "bag").open()
    with pytest.raises(BagError, match="splitting size"):
        Writer(tmp_path / "tiny", max_bag_size=10)
    # a type name from the wire or another bag is checked before it is written into this one
    with (
        Writer(tmp_path / "typed") as writer,
        pytest.raises(BagError, match=r"^Topic '/t': Invalid interface name"),
    ):
        writer.create_topic("/t", "std_msgs/msg/String\n!!python/object")


def test_qos_forms_round_trip() -> None:
    profiles = [LATCHED, QoSProfile(reliability=ReliabilityPolicy.BEST_EFFORT, depth=5)]
    text = dump_qos_list(profiles)
    assert text.startswith("- history: keep_last\n  depth: 1\n  reliability: reliable\n")
    assert not text.endswith("\n")
    assert parse_qos_list(text) == profiles
    assert parse_qos_list(dump_qos_list(profiles, names=False)) == profiles
    assert parse_qos_list("") == [] and dump_qos_list([]) == ""
    # Foxy's "infinite" durations read as rmw's infinite
    legacy = parse_qos_list(
        "- history: 3\n  depth: 0\n  reliability: 1\n  durability: 2\n"
        "  deadline:\n    sec: 2147483647\n    nsec: 4294967295\n"
    )
    assert legacy[0].deadline.is_infinite


def test_library_api_round_trip(tmp_path: Path) -> None:
    now = time.time_ns()
    with Writer(tmp_path / "lib") as bag:
        bag.write("/a", String(data="one"), now)
        tid = bag.create_topic("/raw", "std_msgs/msg/String")
        from ros2lite.interfaces import serialize

        bag.write_raw(tid, serialize(String(data="two")), now + 1, now)
        with pytest.raises(BagError, match="not created"):
            bag.write("/unknown", b"\x00\x01\x00\x00")
    with Reader(tmp_path / "lib") as bag:
        assert [(t, m.data) for t, m, _ in bag] == [("/a", "one"), ("/raw", "two")]
        assert [type(m) for _, m, _ in bag.messages(raw=True)] == [bytes, bytes]
        assert dump_metadata(bag.metadata).startswith("rosbag2_bagfile_information:\n")


def test_metadata_records_the_distro(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """As rosbag2 records its ROS_DISTRO: Jazzy by default, Kilted when that is the distro."""
    import yaml

    for distro, expected in (("", "jazzy"), ("kilted", "kilted")):
        monkeypatch.setenv("ROS_DISTRO", distro)
        with Writer(tmp_path / f"bag_{expected}") as bag:
            bag.write("/chatter", String(data="x"), 1_700_000_000_000_000_000)
        meta = yaml.safe_load((tmp_path / f"bag_{expected}" / "metadata.yaml").read_text())
        assert meta["rosbag2_bagfile_information"]["ros_distro"] == expected
