"""foxglove_bridge benchmarks: what a Foxglove client receives through the bridge, against
the same topic read by a plain ros2lite subscription in the same run.

Each benchmark starts its own router (free loopback port, private domain), the bridge as
`ros2lite run foxglove_bridge foxglove_bridge`, the npm client of tests/js (the protocol's
own `@foxglove/ws-protocol`) and, as the baseline, a raw ros2lite subscription in a process
of its own; a publisher process sends a fixed number of messages once both are subscribed.

* foxglove_string_1khz: 5000 std_msgs/String at 1 kHz; value = messages the client got /
  messages sent (1 means no loss); ratio = client's count / the baseline subscription's.
* foxglove_image_1mib_30hz: 150 sensor_msgs/Image of 1 MiB at 30 Hz; value = the client's
  arrival rate (messages - 1 over first-to-last arrival); ratio = that / the baseline's rate.
* foxglove_stalled_client_latency: the p50 latency of a 200 Hz String topic between two
  other nodes, while the bridge serves a client subscribed to the 1 MiB images that has
  stopped reading its socket; ratio = that / the same latency with the bridge running and no
  client (1 means the stalled client costs the robot nothing).
"""

from __future__ import annotations

import contextlib
import json
import statistics
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path

from bench_topic import private_router
from common import free_port, ready_child, report

ROOT = Path(__file__).resolve().parents[1]

# a raw subscription counting arrivals; prints {count, first, last} when stdin closes
COUNTER = r'''
import json, sys, time
from ros2lite.context import Context
from ros2lite.node import Node
topic, type_name = sys.argv[1], sys.argv[2]
ctx = Context(); ctx.init([])
node = Node('bench_baseline', context=ctx, enable_rosout=False)
seen = {'count': 0, 'first': 0.0, 'last': 0.0}
def got(data, info):
    now = time.monotonic()
    if seen['count'] == 0:
        seen['first'] = now
    seen['last'] = now
    seen['count'] += 1
node.create_subscription(type_name, topic, got, 1000, raw=True)
import threading
from ros2lite.executors import SingleThreadedExecutor
ex = SingleThreadedExecutor(context=ctx); ex.add_node(node)
threading.Thread(target=ex.spin, daemon=True).start()
print('ready', flush=True)
sys.stdin.read()
print(json.dumps(seen), flush=True)
ctx.shutdown()
'''

# sends `count` messages at `hz` once `subscribers` subscriptions match
PUBLISHER = r'''
import sys, time
from ros2lite.context import Context
from ros2lite.node import Node
from ros2lite.interfaces import get_interface, serialize
topic, kind = sys.argv[1], sys.argv[2]
hz, count, subscribers = float(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
ctx = Context(); ctx.init([])
node = Node('bench_source', context=ctx, enable_rosout=False)
if kind == 'image':
    Image = get_interface('sensor_msgs/msg/Image')
    pub = node.create_publisher(Image, topic, 10)
    data = serialize(Image(height=512, width=512, encoding='rgba8', step=2048, data=bytes(1 << 20)))
    payloads = [data] * count
else:
    String = get_interface('std_msgs/msg/String')
    pub = node.create_publisher(String, topic, 10)
    payloads = [serialize(String(data=f'sample {i}')) for i in range(count)]
print('ready', flush=True)
deadline = time.monotonic() + 30
while pub.get_subscription_count() < subscribers and time.monotonic() < deadline:
    time.sleep(0.02)
time.sleep(0.5)
start = time.monotonic()
for i, data in enumerate(payloads):
    ahead = start + i / hz - time.monotonic()
    if ahead > 0:
        time.sleep(ahead)
    pub.publish(data)
time.sleep(1.0)
print('done', flush=True)
sys.stdin.read()
ctx.shutdown()
'''

# two more nodes: a 200 Hz String of send times, and a subscriber of its latencies
LAT_PUB = r'''
import sys, time
from ros2lite.context import Context
from ros2lite.node import Node
from ros2lite.interfaces import get_interface
ctx = Context(); ctx.init([])
node = Node('bench_ping', context=ctx, enable_rosout=False)
String = get_interface('std_msgs/msg/String')
pub = node.create_publisher(String, '/bench_latency', 10)
import threading
done = threading.Event()
threading.Thread(target=lambda: (sys.stdin.read(), done.set()), daemon=True).start()
print('ready', flush=True)
while not done.wait(0.005):
    pub.publish(String(data=str(time.time_ns())))
ctx.shutdown()
'''
LAT_SUB = r'''
import json, sys, time, threading
from ros2lite.context import Context
from ros2lite.node import Node
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface
ctx = Context(); ctx.init([])
node = Node('bench_pong', context=ctx, enable_rosout=False)
lat = []
node.create_subscription(get_interface('std_msgs/msg/String'), '/bench_latency',
                         lambda m: lat.append(time.time_ns() - int(m.data)), 100)
ex = SingleThreadedExecutor(context=ctx); ex.add_node(node)
threading.Thread(target=ex.spin, daemon=True).start()
print('ready', flush=True)
for line in sys.stdin:   # 'mark' starts a new window, 'take' prints its latencies
    if line.strip() == 'mark':
        lat.clear()
    else:
        print(json.dumps(sorted(lat)), flush=True)
ctx.shutdown()
'''


def _client_class() -> type:
    sys.path.insert(0, str(ROOT))
    from tests.bundled.test_foxglove_bridge import JsClient

    return JsClient


@contextlib.contextmanager
def bridge(env: dict[str, str], *params: str) -> Iterator[int]:
    """The bridge on a free port, once it listens; yields the port."""
    port = free_port()
    args = ['--ros-args', '-p', f'port:={port}']
    for p in params:
        args += ['-p', p]
    proc = subprocess.Popen(
        [sys.executable, '-m', 'ros2lite', 'run', 'foxglove_bridge', 'foxglove_bridge', *args],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )
    listening = threading.Event()

    def read() -> None:
        assert proc.stderr is not None
        for line in proc.stderr:
            if 'listening on' in line:
                listening.set()

    threading.Thread(target=read, daemon=True).start()
    try:
        if not listening.wait(30):
            raise RuntimeError('the bridge did not start')
        yield port
    finally:
        proc.terminate()
        proc.wait(10)


def _client(port: int, topic: str) -> object:
    client = _client_class()(port)
    client.channels({topic}, timeout=30)  # type: ignore[attr-defined]
    client.send(cmd='subscribe', topic=topic, decode=0)  # type: ignore[attr-defined]
    return client


def _counts(client: object, topic: str) -> dict[str, float]:
    client.send(cmd='counts')  # type: ignore[attr-defined]
    ev = client.expect(lambda e: e['event'] == 'counts')  # type: ignore[attr-defined]
    got: dict[str, float] = ev['counts'][topic]
    return got


def trial(kind: str, hz: float, count: int) -> tuple[dict[str, float], dict[str, float]]:
    """(the client's counts, the baseline's) for `count` messages of `kind` at `hz`."""
    topic = f'/bench_fox_{kind}'
    type_name = 'sensor_msgs/msg/Image' if kind == 'image' else 'std_msgs/msg/String'
    with (
        private_router() as env,
        bridge(env) as port,
        ready_child(COUNTER, topic, type_name, env=env) as baseline,
        ready_child(PUBLISHER, topic, kind, str(hz), str(count), '2', env=env) as pub,
    ):
        client = _client(port, topic)
        try:
            assert pub.stdout is not None and baseline.stdout is not None
            if pub.stdout.readline().strip() != 'done':
                raise RuntimeError('publisher failed')
            ours = _counts(client, topic)
        finally:
            client.close()  # type: ignore[attr-defined]
        assert baseline.stdin is not None
        baseline.stdin.close()
        theirs: dict[str, float] = json.loads(baseline.stdout.readline())
    # the client's times are ms, the baseline's seconds
    ours['span'] = (ours['last'] - ours['first']) / 1000.0 if ours['received'] else 0.0
    theirs['span'] = theirs['last'] - theirs['first']
    return ours, theirs


def bench_string_1khz() -> None:
    ours, theirs = trial('string', 1000.0, 5000)
    report(
        'foxglove_string_1khz_delivered',
        ours['received'] / 5000,
        'of sent',
        ours['received'] / max(theirs['count'], 1),
    )


def bench_image_30hz() -> None:
    ours, theirs = trial('image', 30.0, 150)
    rate = (ours['received'] - 1) / ours['span'] if ours['span'] else 0.0
    base = (theirs['count'] - 1) / theirs['span'] if theirs['span'] else 0.0
    report('foxglove_image_1mib_30hz_rate', rate, 'Hz', rate / base if base else 0.0)


def _latency_window(sub: subprocess.Popen[str], seconds: float) -> float:
    assert sub.stdin is not None and sub.stdout is not None
    sub.stdin.write('mark\n')
    sub.stdin.flush()
    time.sleep(seconds)
    sub.stdin.write('take\n')
    sub.stdin.flush()
    lat = json.loads(sub.stdout.readline())
    if len(lat) < 10:
        raise RuntimeError(f'only {len(lat)} latency samples')
    return float(statistics.median(lat)) / 1e6


def bench_stalled_client_latency() -> None:
    topic = '/bench_fox_image'
    with (
        private_router() as env,
        bridge(env, 'message_backlog_size:=1024') as port,
        ready_child(PUBLISHER, topic, 'image', '30', '450', '0', env=env),
        ready_child(LAT_SUB, env=env) as sub,
        ready_child(LAT_PUB, env=env),
    ):
        time.sleep(1.0)
        idle = _latency_window(sub, 3.0)
        client = _client(port, topic)
        try:
            deadline = time.monotonic() + 20
            while _counts(client, topic)['received'] < 5:
                if time.monotonic() > deadline:
                    raise RuntimeError('the client got no images')
                time.sleep(0.1)
            client.send(cmd='pause')  # type: ignore[attr-defined]
            time.sleep(1.0)  # its socket buffers fill; the bridge starts dropping for it
            stalled = _latency_window(sub, 3.0)
        finally:
            client.close()  # type: ignore[attr-defined]
    report('foxglove_stalled_client_latency_p50', stalled, 'ms', stalled / idle)


BENCHES = {
    'foxglove_string': bench_string_1khz,
    'foxglove_image': bench_image_30hz,
    'foxglove_stalled': bench_stalled_client_latency,
}
