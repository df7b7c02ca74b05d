"""ROS 1 bags (written here with rosbags' ROS 1 writer) read as ROS 2 bags: info from the
index, messages converted to ROS 2 CDR (Header without seq), latched topics offered
TRANSIENT_LOCAL, and `convert` to MCAP that rosbags and mcap read back."""

from __future__ import annotations

import glob
from pathlib import Path

import numpy as np
import pytest

from ros2lite.bag import BagError, Reader
from ros2lite.bag.convert import OutputBag, convert
from ros2lite.bag.cut import cut
from ros2lite.bag.recorder import RecordOptions
from ros2lite.qos import DurabilityPolicy

T0 = 1_700_000_000_000_000_000


def write_ros1_bag(path: Path, n: int = 10) -> Path:
    """/chatter (String), /imu (Imu, with a Header) and a latched /map_name, ROS 1 style."""
    from rosbags.rosbag1 import Writer
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS1_NOETIC)
    t = ts.types
    with Writer(path) as w:
        chatter = w.add_connection("/chatter", "std_msgs/msg/String", typestore=ts)
        imu = w.add_connection("/imu", "sensor_msgs/msg/Imu", typestore=ts)
        latched = w.add_connection("/map_name", "std_msgs/msg/String", typestore=ts, latching=1)
        w.write(
            latched,
            T0,
            ts.serialize_ros1(t["std_msgs/msg/String"](data="lab"), "std_msgs/msg/String"),
        )
        for k in range(n):
            text = t["std_msgs/msg/String"](data=f"hello {k}")
            w.write(chatter, T0 + k * 10**8, ts.serialize_ros1(text, "std_msgs/msg/String"))
            vec = t["geometry_msgs/msg/Vector3"]
            msg = t["sensor_msgs/msg/Imu"](
                header=t["std_msgs/msg/Header"](
                    seq=k,
                    stamp=t["builtin_interfaces/msg/Time"](sec=7, nanosec=k),
                    frame_id="imu_link",
                ),
                orientation=t["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0),
                orientation_covariance=np.zeros(9),
                angular_velocity=vec(x=0.1 * k, y=0.0, z=0.0),
                angular_velocity_covariance=np.zeros(9),
                linear_acceleration=vec(x=0.0, y=0.0, z=9.81),
                linear_acceleration_covariance=np.arange(9, dtype=np.float64),
            )
            w.write(imu, T0 + k * 10**8 + 1, ts.serialize_ros1(msg, "sensor_msgs/msg/Imu"))
    return path


def test_read_as_a_ros2_bag(tmp_path: Path) -> None:
    bag = write_ros1_bag(tmp_path / "old.bag")
    with Reader(bag) as r:
        assert r.metadata.storage_identifier == "rosbag1"
        assert r.message_count == 21
        assert r.start_time == T0 and r.end_time == T0 + 9 * 10**8 + 1
        types = {t.name: t.type for t in r.topics}
        assert types == {
            "/chatter": "std_msgs/msg/String",
            "/imu": "sensor_msgs/msg/Imu",
            "/map_name": "std_msgs/msg/String",
        }
        latched = r.topic("/map_name")
        assert latched is not None
        assert latched.offered_qos_profiles[0].durability == DurabilityPolicy.TRANSIENT_LOCAL
        imus = [m for topic, m, _ in r.messages(["/imu"])]
        assert len(imus) == 10
        last = imus[-1]
        assert last.header.frame_id == "imu_link" and last.header.stamp.nanosec == 9  # type: ignore[union-attr]
        assert abs(last.angular_velocity.x - 0.9) < 1e-12  # type: ignore[union-attr]
        assert list(last.linear_acceleration_covariance) == [float(i) for i in range(9)]  # type: ignore[union-attr]
        texts = [m.data for _, m, _ in r.messages(["/chatter"], start=T0 + 5 * 10**8)]  # type: ignore[union-attr]
        assert texts == [f"hello {k}" for k in range(5, 10)]


def test_converts_to_mcap_that_independent_readers_open(tmp_path: Path) -> None:
    from mcap.reader import make_reader
    from rosbags.highlevel import AnyReader

    bag = write_ros1_bag(tmp_path / "old.bag")
    [meta] = convert(
        [(bag, None)], [OutputBag(uri=str(tmp_path / "new"), record=RecordOptions(all_topics=True))]
    )
    assert meta.message_count == 21
    with AnyReader([tmp_path / "new"]) as ar:
        got = [(c.topic, ar.deserialize(raw, c.msgtype)) for c, _, raw in ar.messages()]
    assert len(got) == 21
    imu = next(m for topic, m in got if topic == "/imu")
    assert imu.header.frame_id == "imu_link" and not hasattr(imu.header, "seq")
    [f] = glob.glob(str(tmp_path / "new" / "*.mcap"))
    with open(f, "rb") as stream:
        assert sum(1 for _ in make_reader(stream, validate_crcs=True).iter_messages()) == 21
    with Reader(tmp_path / "new") as r:
        latched = r.topic("/map_name")
        assert latched is not None and latched.offered_qos_profiles[0].depth == 1
    # cut and filter take it too (message by message: it is no MCAP file)
    result = cut(bag, tmp_path / "cut", topics=["/chatter"], end=T0 + 2 * 10**8)
    assert not result.spliced and result.metadata.message_count == 3


def test_a_broken_ros1_bag_is_one_line(tmp_path: Path) -> None:
    bad = tmp_path / "bad.bag"
    bad.write_bytes(b"#ROSBAG V2.0\n" + b"\x00" * 100)
    with pytest.raises(BagError, match="not a readable ROS 1 bag"):
        Reader(bad)
