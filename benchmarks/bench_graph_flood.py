"""A flood of liveliness tokens (R-G18/G16): what 10k tokens cost the router, ours beside a
bare Zenoh router, and how soon a new pair of nodes meets while they pour in.

Each router is a process of its own on a free loopback port: the ros2lite daemon (router,
graph cache) and, as the baseline, a bare `zenoh.open` router with Zenoh's defaults. One
client declares `TOKENS` publisher tokens as fast as the router takes them; we time that
(`absorb`), read the router's resident memory before, after, and once the client is gone.
The router's own growth is Zenoh's (the baseline shows it); the ratio is what ours adds.
`graph_flood_pair_meet` is how long two new nodes in one process take from creation to the
first message while a flood is under way, against the same with no flood.
"""

from __future__ import annotations

import os
import random
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager

from common import free_port, ready_child, report

TOKENS = 10_000

FLOOD = '''
import os, sys, time, zenoh
endpoint, domain, count = sys.argv[1], sys.argv[2], int(sys.argv[3])
hash_ = "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18"
config = zenoh.Config()
config.insert_json5("mode", '"client"')
config.insert_json5("connect/endpoints", f'["{endpoint}"]')
config.insert_json5("scouting/multicast/enabled", "false")
session = zenoh.open(config)
zid = os.urandom(16).hex()
tokens = []
start = time.monotonic()
for i in range(count):
    tokens.append(session.liveliness().declare_token(
        f"@ros2_lv/{domain}/{zid}/0/{i + 10}/MP/%/%/floodnode/%flood%t{i}/"
        f"std_msgs::msg::dds_::String_/{hash_}/::,10:,:,:,,"))
    if i % 1000 == 999:
        print(i + 1, flush=True)
print(f"done {time.monotonic() - start:.3f}", flush=True)
time.sleep(120)
'''

PAIR = '''
import time
import ros2lite
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface
String = get_interface("std_msgs/msg/String")
ros2lite.init([])
start = time.monotonic()
listener, talker = ros2lite.Node("pair_listener"), ros2lite.Node("pair_talker")
heard = []
listener.create_subscription(String, "/pair", lambda m: heard.append(1), 10)
publisher = talker.create_publisher(String, "/pair", 10)
executor = SingleThreadedExecutor()
executor.add_node(listener)
executor.add_node(talker)
while not heard and time.monotonic() < start + 30:
    publisher.publish(String(data="hello"))
    executor.spin_once(timeout_sec=0.01)
print(f"{time.monotonic() - start:.3f}", flush=True)
'''

BARE = '''
import sys, zenoh
config = zenoh.Config()
config.insert_json5("mode", '"router"')
config.insert_json5("listen/endpoints", f'["{sys.argv[1]}"]')
config.insert_json5("scouting/multicast/enabled", "false")
router = zenoh.open(config)
print("ready", flush=True)
sys.stdin.read()
'''


def rss_mb(pid: int) -> float:
    with open(f'/proc/{pid}/status') as status:
        for line in status:
            if line.startswith('VmRSS:'):
                return int(line.split()[1]) / 1024
    return 0.0


@contextmanager
def daemon(endpoint: str, env: dict[str, str]) -> Iterator[int]:
    proc = subprocess.Popen(
        [sys.executable, '-m', 'ros2lite.daemon', '--router', endpoint, '--foreground'],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    try:
        deadline = time.monotonic() + 20
        probe = [sys.executable, '-m', 'ros2lite', 'daemon', 'status']
        while time.monotonic() < deadline:
            out = subprocess.run(probe, env=env, capture_output=True, text=True).stdout
            if 'ros2lite daemon' in out:
                break
            time.sleep(0.2)
        yield proc.pid
    finally:
        proc.terminate()
        proc.wait(timeout=10)


@contextmanager
def bare(endpoint: str) -> Iterator[int]:
    with ready_child(BARE, endpoint) as proc:
        yield proc.pid


@contextmanager
def flooding(endpoint: str, domain: str, env: dict[str, str], until: int) -> Iterator[float]:
    """A flooding client; yields once `until` tokens are declared (then the time it took)."""
    proc = subprocess.Popen(
        [sys.executable, '-c', FLOOD, endpoint, domain, str(TOKENS)],
        env=env,
        text=True,
        stdout=subprocess.PIPE,
    )
    assert proc.stdout is not None
    try:
        start = time.monotonic()
        for line in proc.stdout:
            if line.startswith('done') or int(line) >= until:
                break
        yield time.monotonic() - start
    finally:
        proc.kill()
        proc.wait()


def absorb(kind: str) -> tuple[float, float, float]:
    """(seconds to declare TOKENS, RSS growth MB, RSS growth left once they are gone)."""
    with tempfile.TemporaryDirectory() as runtime:
        endpoint = f'tcp/127.0.0.1:{free_port()}'
        domain = str(random.randint(100, 232))
        env = {**os.environ, 'ROS2LITE_ROUTER': endpoint, 'XDG_RUNTIME_DIR': runtime}
        env.update(ROS_DOMAIN_ID=domain, ROS2LITE_NO_DAEMON='1')
        router = daemon(endpoint, env) if kind == 'ours' else bare(endpoint)
        with router as pid:
            time.sleep(1.0)
            before = rss_mb(pid)
            with flooding(endpoint, domain, env, TOKENS) as took:
                time.sleep(1.0)
                grown = rss_mb(pid) - before
            time.sleep(3.0)  # the client is gone: its tokens go
            left = rss_mb(pid) - before
    return took, grown, left


def pair_meet(flood: bool) -> float:
    with tempfile.TemporaryDirectory() as runtime:
        endpoint = f'tcp/127.0.0.1:{free_port()}'
        domain = str(random.randint(100, 232))
        env = {**os.environ, 'ROS2LITE_ROUTER': endpoint, 'XDG_RUNTIME_DIR': runtime}
        env.update(ROS_DOMAIN_ID=domain, ROS2LITE_NO_DAEMON='1')
        with daemon(endpoint, env):
            pair = [sys.executable, '-c', PAIR]
            if not flood:
                return float(subprocess.run(pair, env=env, capture_output=True, text=True).stdout)
            with flooding(endpoint, domain, env, TOKENS * 4 // 10):
                return float(subprocess.run(pair, env=env, capture_output=True, text=True).stdout)


def bench_graph_flood() -> None:
    ours, base = absorb('ours'), absorb('bare')
    report('graph_flood_absorb_10k', ours[0], 's', ours[0] / base[0])
    report('graph_flood_rss_growth_10k', ours[1], 'MB', ours[1] / max(base[1], 0.1))
    report('graph_flood_rss_left_after', ours[2], 'MB', ours[2] / max(base[2], 0.1))
    report('graph_flood_bare_router_rss_growth_10k', base[1], 'MB', 1.0)
    calm = pair_meet(False)
    meet = pair_meet(True)
    report('graph_flood_pair_meet', meet, 's', meet / calm)


BENCHES = {'graph_flood': bench_graph_flood}
