"""A ROS 1 bag made with rosbags plays through a real router to a ROS 2 subscriber, and `bag
info`/`bag echo` read it as they read any bag."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from ros2lite.interfaces import deserialize, get_interface

from ...bag.test_rosbag1 import write_ros1_bag
from .conftest import play, subscribed, wait_until

String = get_interface("std_msgs/msg/String")
Imu = get_interface("sensor_msgs/msg/Imu")


def test_plays_to_a_subscriber(tmp_path: Path, ros_context: Any, listener: Any) -> None:
    bag = write_ros1_bag(tmp_path / "old.bag")
    chatter = listener("/chatter", String, raw=True)
    imu = listener("/imu", Imu)
    wait_until(lambda: subscribed(ros_context, "/chatter") and subscribed(ros_context, "/imu"))
    result = play(str(bag), "-r", "5")
    assert result.returncode == 0, result.stderr
    wait_until(lambda: len(chatter.messages) == 10 and len(imu.messages) == 10)
    got = [deserialize("std_msgs/msg/String", data).data for data in chatter.messages]
    assert got == [f"hello {k}" for k in range(10)]
    assert imu.messages[3].header.frame_id == "imu_link"


def test_info_and_echo(run: Any, tmp_path: Path) -> None:
    bag = write_ros1_bag(tmp_path / "old.bag")
    info = run("bag", "info", str(bag))
    assert info.code == 0 and "Storage id:        rosbag1" in info.out
    assert "Topic: /imu | Type: sensor_msgs/msg/Imu | Count: 10" in info.out
    echo = run("bag", "echo", str(bag), "/chatter", "--field", "data", "-n", "2")
    assert echo.out == "hello 0\n---\nhello 1\n---\n"
