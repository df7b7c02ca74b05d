"""Service benchmarks: request/response round trips through the library against raw
zenoh-python query/reply in the same run, and `ros2lite service call` as a whole process.

A child process runs the router, a raw zenoh queryable and a ros2lite add_two_ints server
(without logging), so both clients in this process cross the same loopback hops.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

from common import cli_env, environment, free_port, import_click_wall, ready_child, report, wall

ROUNDS = 2000
ADD = 'example_interfaces/srv/AddTwoInts'

# Runs in the child: router, raw echo queryable, library server; prints "ready".
_SERVERS = '''
import sys, threading
import zenoh
import ros2lite
from ros2lite.transport.config import router_config
from ros2lite.msgs.example_interfaces.srv import AddTwoInts

endpoint = sys.argv[1]
router = zenoh.open(router_config(endpoint, env={}))
raw = zenoh.open(zenoh.Config.from_json5(
    '{mode: "client", connect: {endpoints: ["%s"]}, scouting: {multicast: {enabled: false}}}'
    % endpoint))

def echo(query):
    with query:
        query.reply(query.key_expr, query.payload, attachment=query.attachment)

queryable = raw.declare_queryable('bench/raw_echo', zenoh.handlers.Callback(echo), complete=True)

def add(request, response):
    response.sum = request.a + request.b
    return response

ros2lite.init([])
node = ros2lite.Node('bench_server', enable_rosout=False)
node.create_service(AddTwoInts, 'bench_add', add)

def serve_until_stdin_closes():
    sys.stdin.read()
    ros2lite.shutdown()

threading.Thread(target=serve_until_stdin_closes, daemon=True).start()
print('ready', flush=True)
ros2lite.spin(node)
queryable.undeclare()
raw.close()
router.close()
'''


def _percentiles(samples: list[float]) -> tuple[float, float]:
    samples.sort()
    return samples[len(samples) // 2], samples[min(len(samples) - 1, len(samples) * 99 // 100)]


def _raw_round_trips(endpoint: str) -> list[float]:
    import zenoh

    conf = zenoh.Config.from_json5(
        f'{{mode: "client", connect: {{endpoints: ["{endpoint}"]}}, '
        'scouting: {multicast: {enabled: false}}}'
    )
    session = zenoh.open(conf)
    try:
        querier = session.declare_querier(
            'bench/raw_echo',
            target=zenoh.QueryTarget.ALL_COMPLETE,
            consolidation=zenoh.ConsolidationMode.NONE,
        )
        payload = b'\x00\x01\x00\x00' + bytes(16)
        attachment = bytes(33)
        times = []
        for i in range(ROUNDS + 100):
            t0 = time.perf_counter()
            replies = list(querier.get(payload=payload, attachment=attachment))
            dt = time.perf_counter() - t0
            assert replies and replies[0].ok is not None
            if i >= 100:
                times.append(dt)
        return times
    finally:
        session.close()


def _library_round_trips() -> list[float]:
    import ros2lite
    from ros2lite.context import Context
    from ros2lite.msgs.example_interfaces.srv import AddTwoInts

    ctx = Context().init([])
    try:
        node = ros2lite.Node('bench_client', context=ctx, enable_rosout=False)
        client = node.create_client(AddTwoInts, 'bench_add')
        assert client.wait_for_service(timeout_sec=10)
        request = AddTwoInts.Request(a=1, b=2)
        times = []
        for i in range(ROUNDS + 100):
            t0 = time.perf_counter()
            response = client.call(request)
            dt = time.perf_counter() - t0
            assert response.sum == 3
            if i >= 100:
                times.append(dt)
        return times
    finally:
        ctx.shutdown()


def bench_service() -> None:
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    domain = '218'
    with tempfile.TemporaryDirectory() as runtime:
        env = cli_env(endpoint, domain, runtime)
        # the child serves until its stdin closes
        with ready_child(_SERVERS, endpoint, env=env, timeout=30), environment(env):
            # interleaved halves, so a slow phase of the machine hits both sides
            raw, ours = [], []
            for _ in range(2):
                raw += _raw_round_trips(endpoint)
                ours += _library_round_trips()
            exe = os.path.join(os.path.dirname(sys.executable), 'ros2lite')
            cmd = [exe, 'service', 'call', '/bench_add', ADD, '{a: 1, b: 2}']
            subprocess.run(cmd, check=True, capture_output=True, timeout=30)
            call_wall = wall(cmd, runs=9)
            base = import_click_wall()
    raw50, raw99 = _percentiles(raw)
    our50, our99 = _percentiles(ours)
    report('service_rtt_p50', our50 * 1e6, 'us', our50 / raw50)
    report('service_rtt_p99', our99 * 1e6, 'us', our99 / raw99)
    report('service_rtt_raw_zenoh_p50', raw50 * 1e6, 'us', 1.0)
    report('service_call_cli_wall', call_wall * 1000, 'ms', call_wall / base)


BENCHES = {'service': bench_service}
