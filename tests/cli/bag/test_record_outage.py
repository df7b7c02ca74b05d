"""`bag record` is a node: it records through a router outage (SIGKILL, 6 s) without losing a
message of a 1 kHz peer publisher, and a recorder killed outright loses at most about its
flush interval."""

from __future__ import annotations

import itertools
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from ros2lite.bag import Reader
from ros2lite.bag.reindex import reindex
from tests.cli.bag.conftest import Recording, on_disk, subscribed
from tests.spinning import wait_until

BENCHMARKS = Path(__file__).resolve().parents[3] / 'benchmarks'


def test_six_second_router_sigkill_loses_nothing(tmp_path: Path) -> None:
    sys.path.insert(0, str(BENCHMARKS))
    try:
        from bench_record_outage import record_through_outage
    finally:
        sys.path.remove(str(BENCHMARKS))
    published, recorded = record_through_outage(str(tmp_path / 'bag'), outage=6.0)
    assert recorded == published == 9000


STAMPER = '''
import sys, time
import ros2lite
from ros2lite.interfaces import get_interface
Int64 = get_interface('std_msgs/msg/Int64')
ros2lite.init([])
node = ros2lite.Node('stamper')
pub = node.create_publisher(Int64, sys.argv[1], 1000)
while pub.get_subscription_count() == 0:
    time.sleep(0.01)
start = time.monotonic()
i = 0
while True:
    pub.publish(Int64(data=time.monotonic_ns()))
    i += 1
    time.sleep(max(0.0, start + i / 1000 - time.monotonic()))
'''


def test_sigkill_loses_only_the_last_flush_interval(
    tmp_path: Path, ros_context: Any, processes: Any, topic: str
) -> None:
    rec = Recording(tmp_path / 'bag', '--topics', topic, '--flush-interval', '100')
    try:
        processes.python(STAMPER, topic)  # the recorder subscribes once it has a publisher
        wait_until(lambda: subscribed(ros_context, topic), timeout=20)
        wait_until(lambda: on_disk(tmp_path / 'bag') >= 1500, timeout=30)  # 1.5 s of it
        killed = time.monotonic_ns()
        rec.proc.send_signal(signal.SIGKILL)
        rec.proc.wait(timeout=10)
    finally:
        if rec.proc.poll() is None:
            rec.proc.kill()
        rec.proc.communicate()
    reindex(tmp_path / 'bag')
    with Reader(tmp_path / 'bag') as bag:
        stamps = [m.data for _, m, _ in bag.messages()]
    assert len(stamps) > 1000
    gaps = [b - a for a, b in itertools.pairwise(stamps)]
    assert max(gaps) < 200_000_000, 'the bag has a hole'
    lost_ms = (killed - stamps[-1]) / 1e6
    # the flush interval, plus delivery and scheduling on a loaded 2-core machine
    assert lost_ms < 100 + 400, lost_ms


def test_the_recorder_says_when_the_graph_is_unreachable(tmp_path: Path) -> None:
    """No router at all: the recorder still starts (a node), and says the graph is away."""
    import os

    from tests.spinning import free_port

    env = dict(os.environ, ROS2LITE_ROUTER=f'tcp/127.0.0.1:{free_port()}')
    env['ROS2LITE_NO_DAEMON'] = '1'
    proc = subprocess.Popen(
        [sys.executable, '-m', 'ros2lite', 'bag', 'record', '-a', '-o', str(tmp_path / 'b')],
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    lines: list[str] = []
    deadline = time.monotonic() + 30
    assert proc.stderr is not None
    while not any('graph is unreachable' in ln for ln in lines):
        assert time.monotonic() < deadline and proc.poll() is None, lines
        lines.append(proc.stderr.readline())
    proc.send_signal(signal.SIGINT)
    proc.communicate(timeout=20)
    assert proc.returncode == 0
