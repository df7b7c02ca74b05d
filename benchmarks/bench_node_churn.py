"""Node churn (the component container's 40 -> 111 MB over 800 load/unload rounds): what a
created-and-destroyed node leaves behind in its process, against raw zenoh-python declaring
and undeclaring as many liveliness tokens of fresh keys as a node has.

rmw_zenoh's tokens carry entity ids from one counter per context, so every node's tokens
are keys never seen before; Zenoh keeps a resource per key expression it has met, and this is
that cost. Each side is a process of its own against a router process.
"""

from __future__ import annotations

import os
import subprocess
import sys

from common import free_port, report, router_process

NODES = 400

CHILD = '''
import os, sys, gc
def rss(): return int(open("/proc/self/statm").read().split()[1]) * 4096
kind, n = sys.argv[1], int(sys.argv[2])
if kind == "nodes":
    import ros2lite
    ros2lite.init([])
    def once(i):
        ros2lite.Node("churn").destroy_node()
else:
    import zenoh
    c = zenoh.Config()
    c.insert_json5("mode", '"peer"')
    c.insert_json5("connect/endpoints", f'["{os.environ["ROS2LITE_ROUTER"]}"]')
    c.insert_json5("scouting/multicast/enabled", "false")
    s = zenoh.open(c)
    per = int(sys.argv[3])
    def once(i):
        for j in range(per):
            s.liveliness().declare_token(f"@ros2_lv/0/abc/{i}/{j}/MP/%/%/churn/%t/x/y/::").undeclare()
for i in range(50):
    once(i)
gc.collect(); before = rss()
for i in range(50, 50 + n):
    once(i)
gc.collect(); print(rss() - before, flush=True)
os._exit(0)
'''


def _grown(kind: str, endpoint: str, *extra: str) -> float:
    env = {**os.environ, 'ROS2LITE_ROUTER': endpoint, 'ROS_DOMAIN_ID': '199'}
    out = subprocess.run(
        [sys.executable, '-c', CHILD, kind, str(NODES), *extra],
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
        check=True,
    ).stdout
    return int(out.split()[-1]) / NODES / 1024


def bench_node_churn() -> None:
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    with router_process(endpoint):
        ours = _grown('nodes', endpoint)
        # a node with parameter services, /rosout and /parameter_events: about 25 tokens
        raw = _grown('tokens', endpoint, '25')
    report('node_churn_kb_per_node', ours, 'KB', ours / raw if raw > 0 else float('nan'))
    report('node_churn_raw_25_fresh_tokens', raw, 'KB', 1.0)


BENCHES = {'node_churn': bench_node_churn}
