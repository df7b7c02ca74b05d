"""`bag burst` through a real router: every message at once whatever the recorded gaps,
`-n` and selection, and its one-line errors."""

from __future__ import annotations

import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from ros2lite.bag import Writer
from ros2lite.interfaces import get_interface

from .conftest import subscribed, wait_until

String = get_interface("std_msgs/msg/String")
T0 = 1_700_000_000_000_000_000
SECOND = 1_000_000_000


def burst(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "ros2lite", "bag", "burst", *args],
        capture_output=True,
        text=True,
        timeout=120,
    )


def test_bursts_a_slow_bag_at_once(
    tmp_path: Path, ros_context: Any, listener: Any, topic: str
) -> None:
    # 120 messages a second apart: played on time this bag lasts two minutes
    with Writer(tmp_path / "bag") as bag:
        for i in range(120):
            bag.write(topic, String(data=str(i)), T0 + i * SECOND)
    lst = listener(topic, String)
    wait_until(lambda: subscribed(ros_context, topic))
    t0 = time.monotonic()
    result = burst(str(tmp_path / "bag"))
    elapsed = time.monotonic() - t0
    assert result.returncode == 0, result.stderr
    assert "Burst 120 message(s)" in result.stderr
    wait_until(lambda: len(lst.messages) == 120)
    assert [m.data for m in lst.messages] == [str(i) for i in range(120)]
    assert elapsed < 60  # half the bag's own length, process start-up included


def test_number_selection_and_offset(
    tmp_path: Path, ros_context: Any, listener: Any, topic: str
) -> None:
    a, b = f"{topic}/a", f"{topic}/b"
    with Writer(tmp_path / "bag") as bag:
        for i in range(30):
            bag.write(a, String(data=f"a{i}"), T0 + i * SECOND)
            bag.write(b, String(data=f"b{i}"), T0 + i * SECOND + 1)
    got_a, got_b = listener(a, String), listener(b, String)
    for name in (a, b):
        wait_until(lambda name=name: subscribed(ros_context, name))
    result = burst(str(tmp_path / "bag"), "--topics", b, "-n", "5", "--start-offset", "10")
    assert result.returncode == 0, result.stderr
    wait_until(lambda: len(got_b.messages) == 5)
    assert [m.data for m in got_b.messages] == [f"b{i}" for i in range(10, 15)]
    assert got_a.messages == []


def test_errors_are_one_line(tmp_path: Path) -> None:
    for args, message in [
        ([str(tmp_path / "none")], "does not exist"),
        ([str(tmp_path), "-m", "/a/b"], "is not OLD:=NEW"),
    ]:
        result = burst(*args)
        assert result.returncode == 1
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("[ERROR] [ros2bag]: "), result.stderr
        assert message in lines[0]
