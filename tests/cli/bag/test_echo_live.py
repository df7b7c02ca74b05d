"""`bag echo` of recorded messages prints what `topic echo` printed of the same messages
live: a publisher, `topic echo` processes (YAML, CSV, and JSON when topic echo has it) and a
`bag record` process on one real router, then `bag echo` of the bag."""

from __future__ import annotations

import math
import os
import shutil
import signal
import subprocess
import sys
import threading
from pathlib import Path
from typing import Any

from ros2lite.interfaces import get_interface
from ros2lite.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy

from .conftest import on_disk, subscribed, wait_until

JointState = get_interface("sensor_msgs/msg/JointState")
KEEP_ALL = QoSProfile(history=HistoryPolicy.KEEP_ALL, reliability=ReliabilityPolicy.RELIABLE)
N = 20


def formats(run: Any) -> list[tuple[str, ...]]:
    have_json = "--json" in run("topic", "echo", "--help").out
    return [(), ("--csv",), *([("--json",)] if have_json else [])]


def test_bag_echo_equals_topic_echo(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, topic: str, run: Any
) -> None:
    pub = node.create_publisher(JointState, topic, KEEP_ALL)
    rec = recording(tmp_path / "bag", "--topics", topic)
    kinds = formats(run)
    echoes = [
        subprocess.Popen(
            [
                sys.executable,
                "-m",
                "ros2lite",
                "topic",
                "echo",
                topic,
                "sensor_msgs/msg/JointState",
                "--qos-reliability",
                "reliable",
                "--qos-history",
                "keep_all",
                *args,
            ],
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            text=True,
            env={**os.environ, "PYTHONUNBUFFERED": "1"},
        )
        for args in kinds
    ]
    live = [""] * len(echoes)

    def collect(k: int) -> None:
        stream = echoes[k].stdout
        assert stream is not None
        for line in stream:
            live[k] += line

    readers = [threading.Thread(target=collect, args=(k,), daemon=True) for k in range(len(echoes))]
    for t in readers:
        t.start()
    try:
        wait_until(lambda: subscribed(ros_context, topic, 1 + len(echoes)), timeout=30)
        for i in range(N):
            msg = JointState(
                name=["a", f"joint_{i}"],
                position=[i * 0.5, math.nan],
                velocity=[math.inf, -1e-300],
                effort=[],
            )
            msg.header.stamp.sec, msg.header.frame_id = i, "base"
            pub.publish(msg)
        wait_until(lambda: on_disk(tmp_path / "bag") == N, timeout=20)
        # each echo has printed all N (its output read as it comes, unbuffered)
        wait_until(lambda: all(text.count("joint_") == N for text in live), timeout=20)
        for proc in echoes:
            proc.send_signal(signal.SIGINT)
            proc.wait(timeout=20)
        for t in readers:
            t.join(timeout=10)
    finally:
        for proc in echoes:
            if proc.poll() is None:
                proc.kill()
                proc.wait()
    code, _, err = rec.finish(signal.SIGINT)
    assert code == 0, err
    for args, text in zip(kinds, live, strict=True):
        assert text.count("joint_") == N, (args, text[-300:])
        replay = run("bag", "echo", str(tmp_path / "bag"), topic, *args)
        assert replay.code == 0, replay.err
        assert replay.out == text, args
        if args == ("--json",) and shutil.which("jq"):
            # the bar as a script checks it: the same documents, keys sorted by jq
            assert jq_sorted(replay.out) == jq_sorted(text)
    # bag export writes topic echo's lines: --csv rows, --jsonl objects
    for fmt, args in (("--csv", ("--csv",)), ("--jsonl", ("--json",))):
        if args not in kinds:
            continue
        out = tmp_path / f"export{fmt}"
        done = run("bag", "export", str(tmp_path / "bag"), topic, fmt, "-o", str(out))
        assert done.code == 0, done.err
        assert out.read_text() == live[kinds.index(args)], fmt


def jq_sorted(text: str) -> str:
    """`jq -S -c .` of NDJSON: each document with its keys sorted."""
    return subprocess.run(
        ["jq", "-S", "-c", "."], input=text, capture_output=True, text=True, check=True, timeout=20
    ).stdout
