"""Client-library throughput: lossless `std_msgs/String` pub→sub through the node API, against
raw zenoh-python moving the same CDR bytes, measured in the same run.

Arrangement (identical for both sides): a router process on a free loopback port, the
*subscriber* in this process and the *publisher* in a child process. Both sides open the
sessions nodes open: peer mode, data on a direct loopback link (the baseline passes
`node_session_mode()` to `ros2lite.transport.config.open_session`). The publisher sends warm-up
samples until the subscriber has heard one (so routes exist and nothing is lost to discovery),
then N samples `Hello World: i` back to back; the subscriber counts them and the rate is N over
the time from the first to the last arrival. Every sample must arrive (KEEP_ALL + RELIABLE;
congestion control BLOCK), otherwise the run fails instead of reporting a lossy rate.

* ros2lite: `create_publisher(String, …, KEEP_ALL)` / `publish(msg)` in the child (message
  objects built beforehand, serialized by `publish`); `create_subscription(String, …,
  KEEP_ALL)` spun by a SingleThreadedExecutor here, the callback getting decoded messages.
* baseline: `declare_publisher(key, RELIABLE, BLOCK)` / `put(cdr)` of the pre-serialized
  payloads, and `declare_subscriber(key, FifoChannel)` drained by a Python thread taking
  `sample.payload.to_bytes()`. (A plain callback subscriber is faster to write but not
  lossless: zenoh-python's callback thread drops samples at these rates.)

Reported: `node_pubsub_string <msg/s> msg/s <ratio vs raw zenoh>`, medians of 7 runs per side,
raw and node runs interleaved (BENCH_NODE_VERBOSE=1 prints every run). On a small shared VM
single runs scatter by ±25 %, which is why medians of interleaved runs are compared.
"""

from __future__ import annotations

import contextlib
import os
import random
import statistics
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

from common import report

N_MESSAGES = 200_000
RUNS = 7
WARMUP = 'warmup'

PUBLISHER = r'''
import sys, threading, time
mode, n, key = sys.argv[1], int(sys.argv[2]), sys.argv[3]
go = threading.Event()
threading.Thread(target=lambda: (sys.stdin.readline(), go.set()), daemon=True).start()
from ros2lite import interfaces
String = interfaces.get_interface('std_msgs/msg/String')
if mode == 'node':
    import ros2lite
    from ros2lite.qos import HistoryPolicy, QoSProfile
    ros2lite.init([])
    node = ros2lite.Node('bench_pub', enable_rosout=False)
    pub = node.create_publisher(String, 'bench_chatter',
                                QoSProfile(history=HistoryPolicy.KEEP_ALL))
    msgs = [String(data=f'Hello World: {i}') for i in range(n)]
    warm = String(data='warmup')
    send = pub.publish
else:
    import zenoh
    from ros2lite.transport.config import node_session_mode, open_session
    session = open_session(mode=node_session_mode())
    pub = session.declare_publisher(key, reliability=zenoh.Reliability.RELIABLE,
                                    congestion_control=zenoh.CongestionControl.BLOCK)
    msgs = [interfaces.serialize(String(data=f'Hello World: {i}')) for i in range(n)]
    warm = interfaces.serialize(String(data='warmup'))
    send = pub.put
print('ready', flush=True)
while not go.is_set():
    send(warm)
    time.sleep(0.01)
for m in msgs:
    send(m)
sys.stdin.readline()   # stay connected until the subscriber has everything
'''


class Flag:
    """A set-once flag that is both Event-like (for the raw side) and a ros2lite Future
    (so the node side can use `spin_until_future_complete`, the idiomatic wait)."""

    def __init__(self) -> None:
        from ros2lite.task import Future

        self.future = Future()

    def set(self) -> None:
        if not self.future.done():
            self.future.set_result(True)

    def is_set(self) -> bool:
        return self.future.done()


class Counter:
    """Counts the N real samples (warm-ups excluded) and times first→last arrival."""

    def __init__(self, n: int) -> None:
        self.n = n
        self.count = 0
        self.first = 0.0
        self.last = 0.0
        self.warm = Flag()
        self.done = Flag()

    def hit(self) -> None:
        self.count += 1
        if self.count == 1:
            self.first = time.perf_counter()
        if self.count == self.n:
            self.last = time.perf_counter()
            self.done.set()

    def rate(self) -> float:
        return (self.n - 1) / (self.last - self.first)


ROUTER = r'''
import sys
import zenoh
from ros2lite.transport.config import router_config
router = zenoh.open(router_config(sys.argv[1], env={}))
print('ready', flush=True)
sys.stdin.read()
router.close()
'''


@contextlib.contextmanager
def private_router() -> Iterator[None]:
    """A router process on a free loopback port and a private domain, exported to sessions.

    A process of its own: in the measuring process it would share zenoh's runtime threads
    with the subscriber, whose full channel can then stall the router itself.
    """
    import socket

    with socket.socket() as sock:
        sock.bind(('127.0.0.1', 0))
        port = sock.getsockname()[1]
    endpoint = f'tcp/127.0.0.1:{port}'
    saved = {
        k: os.environ.get(k)
        for k in (
            'ROS2LITE_ROUTER',
            'ROS_DOMAIN_ID',
            'ZENOH_CONFIG_OVERRIDE',
            'ZENOH_SESSION_CONFIG_URI',
        )
    }
    os.environ.pop('ZENOH_CONFIG_OVERRIDE', None)
    os.environ.pop('ZENOH_SESSION_CONFIG_URI', None)
    router = subprocess.Popen(
        [sys.executable, '-c', ROUTER, endpoint],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    assert router.stdout is not None and router.stdin is not None
    os.environ['ROS2LITE_ROUTER'] = endpoint
    os.environ['ROS_DOMAIN_ID'] = str(random.randint(100, 232))
    try:
        if router.stdout.readline().strip() != 'ready':
            raise RuntimeError('benchmark router did not start')
        yield
    finally:
        router.stdin.close()
        try:
            router.wait(timeout=5)
        except subprocess.TimeoutExpired:
            router.kill()
            router.wait()
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v


def run_once(
    mode: str, n: int, key: str, subscribe: Callable[[Counter], Callable[[Flag, float], None]]
) -> float:
    """One measured run: start the publisher child, let `subscribe` receive, return msg/s.

    `subscribe(counter)` sets up the receiving side and returns `wait(flag, timeout)`, which
    receives until the flag is set or the timeout passes.
    """
    counter = Counter(n)
    wait = subscribe(counter)
    proc = subprocess.Popen(
        [sys.executable, '-c', PUBLISHER, mode, str(n), key],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
    )
    assert proc.stdin is not None and proc.stdout is not None
    try:
        assert proc.stdout.readline().strip() == 'ready'
        wait(counter.warm, 10)
        if not counter.warm.is_set():
            raise RuntimeError('publisher never reached the subscriber')
        proc.stdin.write('go\n')
        proc.stdin.flush()
        wait(counter.done, 8)
        if not counter.done.is_set():
            raise RuntimeError(f'lost samples: {counter.count} of {n} arrived')
        proc.stdin.write('done\n')
        proc.stdin.flush()
        proc.wait(timeout=10)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    return counter.rate()


def bench_node_throughput() -> tuple[float, float]:
    """Median node and raw rates of interleaved runs; prints the report lines."""
    from ros2lite.interfaces import get_interface, serialize, type_hash
    from ros2lite.transport.keys import topic_key

    String = get_interface('std_msgs/msg/String')
    warm_cdr = serialize(String(data=WARMUP))
    with private_router():
        domain = int(os.environ['ROS_DOMAIN_ID'])
        key = topic_key(
            domain, '/bench_chatter', 'std_msgs/msg/String', type_hash('std_msgs/msg/String')
        )
        raw_rates: list[float] = []
        node_rates: list[float] = []
        for _ in range(RUNS):  # interleaved, so drifting machine load hits both alike
            raw_rates.append(raw_run(key, warm_cdr))
            node_rates.append(node_run(key, String))
    ours, base = statistics.median(node_rates), statistics.median(raw_rates)
    if os.environ.get('BENCH_NODE_VERBOSE'):
        print('raw', [round(r) for r in raw_rates], 'node', [round(r) for r in node_rates])
    report('node_pubsub_string', ours, 'msg/s', ours / base)
    report('node_pubsub_string_raw_zenoh', base, 'msg/s', 1.0)
    return ours, base


def raw_run(key: str, warm_cdr: bytes) -> float:
    """Baseline: a FIFO-channel subscriber drained by a Python thread (a plain callback
    subscriber is not lossless here: it drops samples under this load)."""
    import zenoh

    from ros2lite.transport.config import node_session_mode, open_session

    session = open_session(mode=node_session_mode())
    try:

        def subscribe(counter: Counter) -> Callable[[Flag, float], None]:
            sub = session.declare_subscriber(key, zenoh.handlers.FifoChannel(4096))

            def drain() -> None:
                with contextlib.suppress(zenoh.ZError):  # closed with the session
                    for sample in sub.handler:
                        if sample.payload.to_bytes() == warm_cdr:
                            counter.warm.set()
                        else:
                            counter.hit()

            threading.Thread(target=drain, daemon=True).start()
            return lambda flag, timeout: flag.future.wait(timeout) and None

        return run_once('raw', N_MESSAGES, key, subscribe)
    finally:
        session.close()


def node_run(key: str, string_type: Any) -> float:
    """ros2lite: a node's KEEP_ALL subscription, callbacks run by the executor here."""
    from ros2lite.context import Context
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.node import Node
    from ros2lite.qos import HistoryPolicy, QoSProfile

    ctx = Context()
    ctx.init([])
    try:
        node = Node('bench_sub', context=ctx, enable_rosout=False)
        ex = SingleThreadedExecutor(context=ctx)
        ex.add_node(node)

        def subscribe(counter: Counter) -> Callable[[Flag, float], None]:
            def on_msg(msg: Any) -> None:
                if msg.data == WARMUP:
                    counter.warm.set()
                else:
                    counter.hit()

            node.create_subscription(
                string_type, 'bench_chatter', on_msg, QoSProfile(history=HistoryPolicy.KEEP_ALL)
            )
            return lambda flag, timeout: ex.spin_until_future_complete(
                flag.future, timeout_sec=timeout
            )

        return run_once('node', N_MESSAGES, key, subscribe)
    finally:
        ctx.shutdown()


BENCHES = {'node': bench_node_throughput}
