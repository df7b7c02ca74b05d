"""`bag record --snapshot DURATION` as a real process against a real router: nothing reaches
the disk until the ~/snapshot service is called or SIGUSR1 arrives, and then the bag holds the
last DURATION before the trigger, nothing older and nothing after it; each snapshot is a file."""

from __future__ import annotations

import signal
import threading
import time
from pathlib import Path
from typing import Any

from ros2lite.bag import Reader
from ros2lite.interfaces import get_interface
from ros2lite.msgs.rosbag2_interfaces.srv import Snapshot

from .conftest import node_up, on_disk, subscribed, wait_until

String = get_interface("std_msgs/msg/String")
S = 1_000_000_000
KEPT = S // 2  # --snapshot 0.5


def test_snapshot_by_service_then_by_signal(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, topic: str
) -> None:
    pub = node.create_publisher(String, topic, 100)
    bag = tmp_path / "bag"
    rec = recording(bag, "--topics", topic, "--snapshot", "0.5")
    wait_until(lambda: subscribed(ros_context, topic) and node_up(ros_context), timeout=20)
    stop = threading.Event()

    def publish() -> None:  # 50 Hz, each message saying when it was sent
        while not stop.is_set():
            pub.publish(String(data=str(time.time_ns())))
            stop.wait(0.02)

    thread = threading.Thread(target=publish, daemon=True)
    thread.start()
    try:
        time.sleep(1.5)  # well past the half second kept (the bar: nothing older than it)
        assert on_disk(bag) == 0  # buffered only
        client = node.create_client(Snapshot, "/rosbag2_recorder/snapshot")
        assert client.wait_for_service(timeout_sec=10)
        asked = time.time_ns()
        response = client.call(Snapshot.Request(), timeout_sec=10)
        answered = time.time_ns()
        assert response is not None and response.success
        wait_until(lambda: on_disk(bag) > 0, timeout=10)
        time.sleep(1.0)
        rec.proc.send_signal(signal.SIGUSR1)
        signalled = time.time_ns()
        wait_until(lambda: len(list(bag.glob("*.mcap"))) == 2 and on_disk(bag) > 0, timeout=10)
    finally:
        stop.set()
        thread.join()
    code, _out, err = rec.finish(signal.SIGINT)
    assert code == 0, err
    assert "Snapshot: wrote" in err
    with Reader(bag) as r:
        files = r.metadata.files
        assert len(files) == 2
        times = [t for _, _, t in r.messages()]
    first, second = times[: files[0].message_count], times[files[0].message_count :]
    # the service's snapshot: the half second before the call, nothing older, nothing after
    assert asked - KEPT <= min(first) and max(first) <= answered
    assert len(first) >= 10  # ~50 messages a second were sent
    assert max(first) - min(first) <= KEPT
    # the signal's: the half second before it, none of the first snapshot's messages again
    assert min(second) > max(first) and min(second) >= signalled - KEPT - S // 100
    assert max(second) - min(second) <= KEPT and len(second) >= 10
