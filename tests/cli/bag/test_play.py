"""`bag play` through a real router: timing, rate, selection, remapping, offset, loop, /clock,
bags whose types exist only in the bag, and one-line errors."""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from ros2lite.bag import Reader, Writer
from ros2lite.bag.definitions import type_ref
from ros2lite.interfaces import deserialize, get_interface
from ros2lite.interfaces.hashing import type_hash

from .conftest import play, subscribed, wait_until

String = get_interface("std_msgs/msg/String")
Clock = get_interface("rosgraph_msgs/msg/Clock")
DATA = Path(__file__).parents[2] / "bag" / "data"
T0 = 1_700_000_000_000_000_000
STEP = 20_000_000  # 20 ms between messages


def make_bag(path: Path, topics: list[str], count: int = 20) -> Path:
    with Writer(path) as bag:
        for i in range(count):
            for j, name in enumerate(topics):
                bag.write(name, String(data=f"{name} {i}"), T0 + i * STEP + j)
    return path


def test_plays_every_message_on_time(
    tmp_path: Path, ros_context: Any, listener: Any, topic: str
) -> None:
    bag = make_bag(tmp_path / "bag", [topic])
    lst = listener(topic, String, raw=True)
    wait_until(lambda: subscribed(ros_context, topic))
    result = play(str(bag))
    assert result.returncode == 0, result.stderr
    assert "Playback until timestamp: -1" in result.stderr
    wait_until(lambda: len(lst.messages) == 20)
    got = [deserialize("std_msgs/msg/String", data).data for data in lst.messages]
    assert got == [f"{topic} {i}" for i in range(20)]
    # 19 gaps of 20 ms, stamped on arrival: never faster than recorded, not much slower
    span = (lst.arrivals[-1] - lst.arrivals[0]) / 1e9
    assert 0.38 * 0.9 <= span <= 0.38 + 0.5


def test_rate_selection_remap_and_offset(
    tmp_path: Path, ros_context: Any, listener: Any, topic: str
) -> None:
    a, b, c = f"{topic}/a", f"{topic}/b", f"{topic}/c"
    bag = make_bag(tmp_path / "bag", [a, b, c])
    to_new = listener(f"{topic}/renamed", String)
    got_b, got_c = listener(b, String), listener(c, String)
    for name in (f"{topic}/renamed", b, c):
        wait_until(lambda name=name: subscribed(ros_context, name))
    t0 = time.monotonic()
    result = play(
        str(bag),
        "-r",
        "4",
        "--exclude-topics",
        c,
        "--remap",
        f"{a}:={topic}/renamed",
        "--start-offset",
        "0.2",
    )
    elapsed = time.monotonic() - t0
    assert result.returncode == 0, result.stderr
    wait_until(lambda: len(to_new.messages) == 10 and len(got_b.messages) == 10)
    assert [m.data for m in to_new.messages] == [f"{a} {i}" for i in range(10, 20)]
    assert got_c.messages == []
    assert elapsed < 0.2 / 4 + 5  # 0.18 s of bag at 4x, plus the process start-up


def test_loop_until_interrupted_and_clock(
    tmp_path: Path, ros_context: Any, listener: Any, topic: str
) -> None:
    bag = make_bag(tmp_path / "bag", [topic], count=5)
    lst = listener(topic, String)
    clock = listener("/clock", Clock, 10)
    wait_until(lambda: subscribed(ros_context, topic))
    proc = subprocess.Popen(
        [sys.executable, "-m", "ros2lite", "bag", "play", str(bag), "-l", "--clock", "100"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        wait_until(lambda: len(lst.messages) >= 12, timeout=20)
    finally:
        proc.send_signal(signal.SIGINT)
        _out, err = proc.communicate(timeout=10)
    assert proc.returncode == 0, err
    assert [m.data for m in lst.messages[:10]] == [f"{topic} {i % 5}" for i in range(10)]
    assert clock.messages
    stamps = [m.clock.sec * 10**9 + m.clock.nanosec for m in clock.messages]
    assert all(T0 <= s <= T0 + 4 * STEP + 1 for s in stamps)


def test_types_known_only_from_the_bag_are_played_raw(
    ros_context: Any,
    listener: Any,
) -> None:
    bag = DATA / "mcap" / "cdr_test"
    with Reader(bag) as reader:
        expected = [data for topic, data, _ in reader.messages(raw=True) if topic == "/test_topic"]
        digest = type_hash("test_msgs/msg/BasicTypes", reader.bag_types())
    assert digest.startswith("RIHS01_")
    lst = listener("/test_topic", type_ref("test_msgs/msg/BasicTypes", digest), raw=True)
    wait_until(lambda: subscribed(ros_context, "/test_topic"))
    result = play(str(bag), "--topics", "/test_topic", "-r", "10")
    assert result.returncode == 0, result.stderr
    wait_until(lambda: len(lst.messages) == 3)
    assert lst.messages == expected


def test_bad_bags_are_one_line_errors(tmp_path: Path, ros_router: str) -> None:
    missing = play(str(tmp_path / "nope"))
    assert (missing.returncode, missing.stderr) == (
        1,
        f"[ERROR] [ros2bag]: Bag path '{tmp_path / 'nope'}' does not exist!\n",
    )
    (tmp_path / "bad.mcap").write_bytes(b"\x89MCAP0\r\n" + b"\x00" * 40)
    corrupt = play(str(tmp_path / "bad.mcap"))
    assert corrupt.returncode == 1 and len(corrupt.stderr.splitlines()) == 1
    assert corrupt.stderr.startswith("[ERROR] [ros2bag]:")
    rate = play(str(tmp_path / "bad.mcap"), "-r", "0")
    assert rate.returncode == 2 and "Traceback" not in rate.stderr


def test_recorded_qos_and_overrides_reach_the_publishers(
    tmp_path: Path, ros_context: Any, topic: str
) -> None:
    from ros2lite.graph import snapshot
    from ros2lite.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

    latched = QoSProfile(durability=DurabilityPolicy.TRANSIENT_LOCAL, depth=4)
    with Writer(tmp_path / "bag") as bag:
        for name in (f"{topic}/latched", f"{topic}/plain"):
            bag.create_topic(name, "std_msgs/msg/String", offered_qos_profiles=[latched])
            for i in range(3):
                bag.write(name, String(data="x"), T0 + i * STEP)
    overrides = tmp_path / "qos.yaml"
    overrides.write_text(f"{topic}/plain:\n  reliability: best_effort\n  depth: 3\n")
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "ros2lite",
            "bag",
            "play",
            str(tmp_path / "bag"),
            "-l",
            "--qos-profile-overrides-path",
            str(overrides),
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )

    def publishers() -> dict[str, Any]:
        return {
            e.topic_name: e.qos
            for e in snapshot(ros_context.session, ros_context.domain_id)
            if e.kind.value == "MP" and (e.topic_name or "").startswith(topic)
        }

    try:
        found = wait_until(lambda: len(publishers()) == 2 and publishers(), timeout=20)
    finally:
        proc.send_signal(signal.SIGINT)
        proc.communicate(timeout=10)
    assert found[f"{topic}/latched"].durability == DurabilityPolicy.TRANSIENT_LOCAL
    assert found[f"{topic}/latched"].reliability == ReliabilityPolicy.RELIABLE
    assert found[f"{topic}/plain"].reliability == ReliabilityPolicy.BEST_EFFORT
    assert found[f"{topic}/plain"].durability == DurabilityPolicy.VOLATILE
    assert found[f"{topic}/plain"].depth == 3
