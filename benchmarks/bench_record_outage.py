"""`bag record` through a router outage: messages of a 1 kHz peer publisher lost while the
router is SIGKILLed for `OUTAGE` s.

A router of our own on a free loopback port (private domain, no auto-start), a publisher node
sending a counter at 1 kHz (reliable, KEEP_ALL) and `ros2lite bag record` of its topic, each its
own process. After a second of traffic the router is killed outright, and started again
`OUTAGE` s later; when the publisher is done the recorder is stopped (SIGINT) and the bag read.
`bag_record_outage_lost` is how many counter values the bag misses; the baseline is the same
run with the recorder forced into a client session (`ZENOH_CONFIG_OVERRIDE='mode="client"'`),
which is what `bag record` was before it became a node.
"""

from __future__ import annotations

import os
import random
import signal
import socket
import subprocess
import sys
import tempfile
import time
from typing import Any

from common import cli_env, free_port, report

OUTAGE = 6.0
RATE = 1000
AFTER = 3.0  # seconds of publishing besides the outage
TOPIC = '/outage_counter'

PUBLISHER = '''
import sys, time
import ros2lite
from ros2lite.interfaces import get_interface
from ros2lite.qos import QoSProfile, HistoryPolicy, ReliabilityPolicy
Int64 = get_interface('std_msgs/msg/Int64')
ros2lite.init([])
node = ros2lite.Node('outage_counter')
qos = QoSProfile(history=HistoryPolicy.KEEP_ALL, reliability=ReliabilityPolicy.RELIABLE)
pub = node.create_publisher(Int64, sys.argv[1], qos)
n, rate = int(sys.argv[2]), float(sys.argv[3])
deadline = time.monotonic() + 60
while pub.get_subscription_count() == 0 and time.monotonic() < deadline:
    time.sleep(0.01)
print('publishing', flush=True)
start = time.monotonic()
for i in range(n):
    pub.publish(Int64(data=i))
    time.sleep(max(0.0, start + (i + 1) / rate - time.monotonic()))
print('done', flush=True)
time.sleep(1.0)  # reliable: let the last samples reach the recorder
'''


def _router(endpoint: str, env: dict[str, str]) -> subprocess.Popen[str]:
    proc = subprocess.Popen(
        [sys.executable, '-m', 'ros2lite.daemon', '--router', endpoint, '--foreground'],
        env=env,
        text=True,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    host, port = endpoint.split('/')[1].rsplit(':', 1)
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        with socket.socket() as sock:
            if sock.connect_ex((host, int(port))) == 0:
                return proc
        time.sleep(0.05)
    proc.kill()
    raise RuntimeError(f'no router came up at {endpoint}')


def record_through_outage(
    bag: str, *, outage: float = OUTAGE, recorder_mode: str | None = None
) -> tuple[int, int]:
    """One run; returns (messages published, distinct counter values in the bag)."""
    with tempfile.TemporaryDirectory() as runtime:
        endpoint = f'tcp/127.0.0.1:{free_port()}'
        env = cli_env(endpoint, str(random.randint(100, 232)), runtime)
        env['ROS2LITE_NO_DAEMON'] = '1'
        return _run(bag, outage, recorder_mode, endpoint, env)


def _run(
    bag: str, outage: float, recorder_mode: str | None, endpoint: str, env: dict[str, str]
) -> tuple[int, int]:
    from ros2lite.bag import Reader

    rec_env = dict(env)
    if recorder_mode:
        rec_env['ZENOH_CONFIG_OVERRIDE'] = f'mode="{recorder_mode}"'
    total = int(RATE * (outage + AFTER))
    router = _router(endpoint, env)
    procs: list[subprocess.Popen[str]] = [router]
    try:
        recorder = subprocess.Popen(
            [sys.executable, '-m', 'ros2lite', 'bag', 'record', '--topics', TOPIC, '-o', bag],
            env=rec_env,
            text=True,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
        )
        procs.append(recorder)
        publisher = subprocess.Popen(
            [sys.executable, '-c', PUBLISHER, TOPIC, str(total), str(RATE)],
            env=env,
            text=True,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
        )
        procs.append(publisher)
        assert publisher.stdout is not None
        if publisher.stdout.readline().strip() != 'publishing':
            raise RuntimeError('the publisher never saw the recorder')
        time.sleep(1.0)
        router.send_signal(signal.SIGKILL)
        router.wait()
        time.sleep(outage)
        router = _router(endpoint, env)
        procs.append(router)
        if publisher.stdout.readline().strip() != 'done':
            raise RuntimeError('the publisher did not finish')
        publisher.wait(timeout=30)
        recorder.send_signal(signal.SIGINT)
        _, err = recorder.communicate(timeout=60)
        if recorder.returncode != 0:
            raise RuntimeError(f'bag record failed: {err}')
    finally:
        for proc in procs:
            if proc.poll() is None:
                proc.kill()
                proc.wait()
    with Reader(bag) as reader:
        seen = {m.data for _, m, _ in reader.messages()}
    return total, len(seen)


def bench_record_outage() -> None:
    with tempfile.TemporaryDirectory() as tmp:
        total, peer = record_through_outage(os.path.join(tmp, 'peer'))
        _, client = record_through_outage(os.path.join(tmp, 'client'), recorder_mode='client')
    lost, lost_client = total - peer, total - client
    report('bag_record_outage_lost', lost, 'msgs', lost / max(lost_client, 1))
    report('bag_record_outage_lost_client_mode', lost_client, 'msgs', 1.0)


BENCHES: dict[str, Any] = {'bag_record_outage': bench_record_outage}
