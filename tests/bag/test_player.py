"""The Player's schedule and controls, driven from the library: never early, rate, delay,
pause / play-next / resume, stop during a loop, and playback QoS from the recorded offers."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from ros2lite.bag import Reader, Writer
from ros2lite.bag.player import Player, PlayOptions
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from tests.spinning import wait_until

String = get_interface("std_msgs/msg/String")
T0 = 1_700_000_000_000_000_000


@pytest.fixture
def node(ros_context: Any) -> Iterator[Node]:
    n = Node("player_test", context=ros_context, enable_rosout=False)
    yield n
    n.destroy_node()


def make_bag(path: Path, count: int, step_ns: int) -> Reader:
    with Writer(path) as bag:
        for i in range(count):
            bag.write("/player_test", String(data=str(i)), T0 + i * step_ns)
    return Reader(path)


def run(player: Player) -> threading.Thread:
    thread = threading.Thread(target=player.play, daemon=True)
    thread.start()
    return thread


def test_schedule_is_never_early_and_follows_the_rate(tmp_path: Path, node: Node) -> None:
    reader = make_bag(tmp_path / "bag", 11, 100_000_000)  # 1 s of bag
    player = Player(node, reader, PlayOptions(rate=4.0, record_timing=True))
    t0 = time.monotonic()
    player.play()
    elapsed = time.monotonic() - t0
    assert player.published == 11
    assert all(late >= 0 for late in player.lateness)  # a message never leaves early
    assert 0.25 <= elapsed < 0.25 + 1.0
    assert player.bag_time() == reader.end_time


def test_delay_pause_play_next_and_resume(tmp_path: Path, node: Node) -> None:
    reader = make_bag(tmp_path / "bag", 5, 50_000_000)
    player = Player(node, reader, PlayOptions(start_paused=True, delay=0.2))
    thread = run(player)
    time.sleep(0.4)
    assert player.published == 0 and player.paused
    player.play_next()
    wait_until(lambda: player.published == 1)
    assert player.bag_time() == T0  # paused: bag time stands at the message played
    time.sleep(0.2)
    assert player.published == 1
    assert player.set_rate(2.0) and not player.set_rate(0)
    t0 = time.monotonic()
    player.resume()
    thread.join(5)
    assert not thread.is_alive() and player.published == 5
    # 3 gaps of 50 ms at twice the speed (the delay only applies before the first message)
    assert 0.075 <= time.monotonic() - t0 < 0.075 + 1.0


def test_stop_ends_a_loop(tmp_path: Path, node: Node) -> None:
    reader = make_bag(tmp_path / "bag", 3, 10_000_000)
    player = Player(node, reader, PlayOptions(loop=True, rate=10))
    thread = run(player)
    wait_until(lambda: player.published >= 9)  # three times round
    player.stop()
    thread.join(2)
    assert not thread.is_alive() and player.stopped


def test_burst_ignores_timing_and_resumes_where_it_stopped(tmp_path: Path, node: Node) -> None:
    # 3 messages share each log time: a burst stopping in the middle of them must resume
    # with the next one, neither repeating nor skipping any
    with Writer(tmp_path / "bag") as bag:
        for i in range(12):
            bag.write("/player_test", String(data=str(i)), T0 + (i // 3) * 10_000_000_000)
    got: list[str] = []
    sub = node.create_subscription(String, "/player_test", lambda m: got.append(m.data), 100)
    player = Player(node, Reader(tmp_path / "bag"), PlayOptions())
    t0 = time.monotonic()
    assert player.burst(4) == 4
    assert player.burst(4) == 4
    assert player.burst() == 4  # the rest
    assert player.burst() == 0
    assert time.monotonic() - t0 < 10  # the bag spans 30 s
    from ros2lite.executors import SingleThreadedExecutor

    executor = SingleThreadedExecutor(context=node.context)
    executor.add_node(node)
    wait_until(lambda: executor.spin_once(0.05) or len(got) == 12)
    assert got == [str(i) for i in range(12)]
    node.destroy_subscription(sub)
    with pytest.raises(ValueError):
        player.burst(-1)
