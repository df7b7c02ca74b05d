"""Publishers, listeners and recorder processes for the bag verbs, over the session router."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import uuid
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from ros2lite.node import Node
from tests.spinning import Listener, wait_until


@pytest.fixture
def topic() -> str:
    """A topic name no other test uses."""
    return f"/bag_{uuid.uuid4().hex[:10]}"


def subscribed(ctx: Any, topic: str, count: int = 1) -> bool:
    """True once the graph shows `count` subscriptions on the topic."""
    from ros2lite.graph import snapshot

    return (
        sum(
            1
            for e in snapshot(ctx.session, ctx.domain_id)
            if e.kind.value == "MS" and e.topic_name == topic
        )
        >= count
    )


class Recording:
    """A `bag record` process writing into `path`."""

    def __init__(self, path: Path, *args: str, preexec: Callable[[], Any] | None = None) -> None:
        self.path = path
        self.proc = subprocess.Popen(
            [sys.executable, "-m", "ros2lite", "bag", "record", "-o", str(path), *args],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            preexec_fn=preexec,
        )

    def finish(self, sig: int = signal.SIGINT, timeout: float = 20) -> tuple[int, str, str]:
        if self.proc.poll() is None:
            self.proc.send_signal(sig)
        out, err = self.proc.communicate(timeout=timeout)
        return self.proc.returncode, out, err


@pytest.fixture
def recording(ros_router: str) -> Iterator[Callable[..., Recording]]:
    made: list[Recording] = []

    def start(path: Path, *args: str, **kw: Any) -> Recording:
        r = Recording(path, *args, **kw)
        made.append(r)
        return r

    yield start
    for r in made:
        if r.proc.poll() is None:
            r.proc.kill()
            r.proc.communicate()


@pytest.fixture
def listener(ros_context: Any) -> Iterator[Callable[..., Listener]]:
    made: list[Listener] = []

    def start(topic: str, type_name: Any, qos: Any = 1000, raw: bool = False) -> Listener:
        lst = Listener(ros_context, topic, type_name, qos, raw)
        made.append(lst)
        return lst

    yield start
    for lst in made:
        lst.stop()


@pytest.fixture
def node(ros_context: Any) -> Iterator[Node]:
    n = Node(f"bag_test_{uuid.uuid4().hex[:6]}", context=ros_context, enable_rosout=False)
    yield n
    n.destroy_node()


def play(*args: str, timeout: float = 30) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "ros2lite", "bag", "play", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
        env={**os.environ},
    )


__all__ = ["Listener", "Recording", "play", "subscribed", "wait_until"]


def on_disk(path: Path, topic: str | None = None) -> int:
    """Messages (of `topic`, or all) that the recording at `path` has put on disk so far, its
    files read as a killed recorder's are: up to their last finished chunk. Polling this
    waits exactly as long as the recorder takes, where a sleep would guess."""
    from ros2lite.bag.storage.mcap import open_reader

    total = 0
    for file in sorted(path.glob("*.mcap")):
        if file.stat().st_size == 0:
            continue  # created, nothing written yet
        reader = open_reader(str(file))
        try:
            summary = reader.summary()
        finally:
            reader.close()
        total += summary.counts.get(topic, 0) if topic else summary.message_count
    return total


def node_up(ctx: Any, name: str = "rosbag2_recorder") -> bool:
    """True once the graph shows a node of that name (a recorder that has started)."""
    from ros2lite.graph import snapshot

    return any(e.node_name == name for e in snapshot(ctx.session, ctx.domain_id))
