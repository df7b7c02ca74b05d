"""Client-library pub→sub through the node API, against raw zenoh-python moving the same CDR
bytes, measured in the same run: throughput of small and 1 MiB messages, and latency.

Arrangement (identical for both sides): a router process on a free loopback port, the
*subscriber* in this process and the *publisher* in a child process. Both sides open the
sessions nodes open: peer mode, data on a direct loopback link (the baseline passes
`node_session_mode()` to `ros2lite.transport.open.open_session`). The publisher sends warm-up
samples until the subscriber has heard one (so routes exist and nothing is lost to discovery),
then N samples back to back; the subscriber counts them and the rate is N over the time from
the first to the last arrival. Every sample must arrive (KEEP_ALL + RELIABLE; congestion
control BLOCK), otherwise the run fails instead of reporting a lossy rate.

* ros2lite: `create_publisher(T, …, KEEP_ALL)` / `publish(msg)` in the child (message objects
  built beforehand, serialized by `publish`); `create_subscription(T, …, KEEP_ALL)` here, the
  callback getting decoded messages, spun either by `spin_until_future_complete` (what
  `spin()` does per turn) or, as many tutorials do, by `while ok(): spin_once(node)` on the
  global executor (`_spin_once` lines).
* baseline: `declare_publisher(key, RELIABLE, BLOCK)` / `put(cdr)` of the pre-serialized
  payloads, and `declare_subscriber(key, FifoChannel)` drained by a Python thread taking
  `sample.payload.to_bytes()`. (A plain callback subscriber is faster to write but not
  lossless: zenoh-python's callback thread drops samples at these rates.) The raw side sends
  no rmw_zenoh attachment; ros2lite must (33 bytes per sample: sequence number, timestamp,
  GID), which zenoh-python charges on both ends. `node_pubsub_string_raw_attachment` shows
  that cost: the same raw pair with the attachment put on every sample (ratio vs raw).
* image: `sensor_msgs/Image` 512x512 rgba8 (1 MiB of `data`); the callback reads
  `len(msg.data)`, the raw side `len(payload.to_bytes())`. Reported in MB/s (10^6 B). Every
  process here, raw ones included, runs with the allocator setting a node makes
  (`ros2lite.runtime.memory`: large buffers reused instead of mapped and unmapped per message).
* latency: ping-pong, the child echoing each `std_msgs/String` ping back on a second topic
  (node: a subscription callback publishing; raw: a FIFO-channel loop putting); this process
  sends the next ping when the pong of the last arrives. Round-trip p50 and p99 in µs over
  2000 pings after a warm-up; ratio = ours / raw.

Medians of RUNS runs per side, the sides interleaved so drifting machine load hits both alike
(BENCH_NODE_VERBOSE=1 prints every run, and the publisher's own send rate). On a small shared
VM single runs scatter by ±25 %, which is why medians of interleaved runs are compared.
"""

from __future__ import annotations

import contextlib
import os
import random
import statistics
import sys
import threading
import time
from collections.abc import Callable, Iterator
from typing import Any

from common import environment, free_port, ready_child, report, router_process

N_MESSAGES = 200_000
N_IMAGES = 400
N_PINGS = 2000
RUNS = int(os.environ.get('BENCH_RUNS', 5))  # interleaved runs per side (median)
WARMUP = 'warmup'
VERBOSE = bool(os.environ.get('BENCH_NODE_VERBOSE'))
STRING = 'std_msgs/msg/String'
# what would replace the sessions' built-in configuration
_CONFIG_VARS = ('ZENOH_CONFIG_OVERRIDE', 'ZENOH_SESSION_CONFIG_URI')
IMAGE = 'sensor_msgs/msg/Image'

# the publisher child: argv = mode (node, raw, rawatt), kind (string, image), n, key
PUBLISHER = r'''
import sys, threading, time
mode, kind, n, key = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4]
go = threading.Event()
threading.Thread(target=lambda: (sys.stdin.readline(), go.set()), daemon=True).start()
from array import array
from ros2lite import interfaces
if kind == 'string':
    T = interfaces.get_interface('std_msgs/msg/String')
    msgs = [T(data=f'Hello World: {i}') for i in range(n)]
    warm = T(data='warmup')
else:
    T = interfaces.get_interface('sensor_msgs/msg/Image')
    image = T(height=512, width=512, encoding='rgba8', step=2048,
              data=array('B', bytes(range(256))) * 4096)
    msgs = [image] * n
    warm = T(encoding='warmup')
if mode == 'node':
    import ros2lite
    from ros2lite.qos import HistoryPolicy, QoSProfile
    ros2lite.init([])
    node = ros2lite.Node('bench_pub', enable_rosout=False)
    topic = 'bench_chatter' if kind == 'string' else 'bench_image'
    pub = node.create_publisher(T, topic, QoSProfile(history=HistoryPolicy.KEEP_ALL))
    send = pub.publish
else:
    import zenoh
    from ros2lite.runtime.memory import keep_large_buffers
    from ros2lite.transport.attachment import pack_attachment
    keep_large_buffers()  # the allocator setting a node has: the same terms for both
    from ros2lite.transport.config import node_session_mode
    from ros2lite.transport.open import open_session
    from ros2lite.daemon.security import session_security
    security = session_security()  # as nodes have it (a secured graph too)
    session = open_session(mode=node_session_mode(security=security), security=security)
    zpub = session.declare_publisher(key, reliability=zenoh.Reliability.RELIABLE,
                                     congestion_control=zenoh.CongestionControl.BLOCK)
    msgs = [interfaces.serialize(m) for m in msgs]
    warm = interfaces.serialize(warm)
    send = zpub.put
    if mode == 'rawatt':  # what rmw_zenoh needs on every sample, nothing else
        put, gid, clock, seq = zpub.put, bytes(16), time.time_ns, iter(range(1, 1 << 62))
        def send(m):
            put(m, attachment=pack_attachment(next(seq), clock(), gid))
print('ready', flush=True)
while not go.is_set():
    send(warm)
    time.sleep(0.01)
t0 = time.perf_counter()
for m in msgs:
    send(m)
print(n / (time.perf_counter() - t0), flush=True)
sys.stdin.readline()   # stay connected until the subscriber has everything (stdin closes)
'''

# the latency echo child: argv = mode (node, raw), ping key, pong key
ECHO = r'''
import sys
mode, ping_key, pong_key = sys.argv[1], sys.argv[2], sys.argv[3]
if mode == 'node':
    import threading
    import ros2lite
    from ros2lite.interfaces import get_interface
    String = get_interface('std_msgs/msg/String')
    ros2lite.init([])
    node = ros2lite.Node('bench_echo', enable_rosout=False)
    pong = node.create_publisher(String, 'bench_pong', 10)
    node.create_subscription(String, 'bench_ping', pong.publish, 10)
    threading.Thread(target=lambda: (sys.stdin.read(), ros2lite.shutdown()), daemon=True).start()
    print('ready', flush=True)
    ros2lite.spin(node)
else:
    import threading
    import zenoh
    from ros2lite.runtime.memory import keep_large_buffers
    from ros2lite.transport.config import node_session_mode
    from ros2lite.transport.open import open_session
    from ros2lite.daemon.security import session_security
    keep_large_buffers()
    security = session_security()  # as nodes have it (a secured graph too)
    session = open_session(mode=node_session_mode(security=security), security=security)
    pub = session.declare_publisher(pong_key)
    sub = session.declare_subscriber(ping_key, zenoh.handlers.FifoChannel(64))

    def echo(put=pub.put, channel=sub.handler):
        try:
            for sample in channel:
                put(sample.payload.to_bytes())
        except zenoh.ZError:
            pass

    thread = threading.Thread(target=echo)
    thread.start()
    print('ready', flush=True)
    sys.stdin.read()
    sub.undeclare()
    thread.join()
    session.close()
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


@contextlib.contextmanager
def private_router() -> Iterator[None]:
    """A router process on a free loopback port and a private domain, exported to sessions.

    A process of its own: in the measuring process it would share zenoh's runtime threads
    with the subscriber, whose full channel can then stall the router itself.
    """
    from ros2lite.runtime.memory import keep_large_buffers

    keep_large_buffers()  # as nodes do: the raw side measured here gets it too
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    env = {k: v for k, v in os.environ.items() if k not in _CONFIG_VARS}
    env.update(ROS2LITE_ROUTER=endpoint, ROS_DOMAIN_ID=str(random.randint(100, 232)))
    with environment(env), router_process(endpoint):
        yield


def _key(type_name: str, topic: str) -> str:
    from ros2lite.interfaces import type_hash
    from ros2lite.transport.keys import topic_key

    return topic_key(int(os.environ['ROS_DOMAIN_ID']), topic, type_name, type_hash(type_name))


Subscribe = Callable[[Counter], Callable[[Flag, float], None]]


def run_once(mode: str, kind: str, n: int, key: str, subscribe: Subscribe) -> float:
    """One measured run: start the publisher child, let `subscribe` receive, return msg/s.

    `subscribe(counter)` sets up the receiving side and returns `wait(flag, timeout)`, which
    receives until the flag is set or the timeout passes.
    """
    counter = Counter(n)
    wait = subscribe(counter)
    with ready_child(PUBLISHER, mode, kind, str(n), key) as proc:
        assert proc.stdin is not None and proc.stdout is not None
        wait(counter.warm, 10)
        if not counter.warm.is_set():
            raise RuntimeError('publisher never reached the subscriber')
        proc.stdin.write('go\n')
        proc.stdin.flush()
        wait(counter.done, 20)
        if not counter.done.is_set():
            raise RuntimeError(f'lost samples: {counter.count} of {n} arrived')
        sent = float(proc.stdout.readline())
    if VERBOSE:
        print(
            f'  {mode}/{kind}: received {counter.rate():.0f}/s, publisher sent {sent:.0f}/s',
            file=sys.stderr,
        )
    return counter.rate()


def raw_run(key: str, warm_cdr: bytes, kind: str, n: int, pub_mode: str = 'raw') -> float:
    """Baseline: a FIFO-channel subscriber drained by a Python thread (a plain callback
    subscriber is not lossless here: it drops samples under this load)."""
    import zenoh

    from ros2lite.daemon.security import session_security
    from ros2lite.transport.config import node_session_mode
    from ros2lite.transport.open import open_session

    security = session_security()  # as nodes have it (a secured graph too)
    session = open_session(mode=node_session_mode(security=security), security=security)
    try:

        def subscribe(counter: Counter) -> Callable[[Flag, float], None]:
            sub = session.declare_subscriber(key, zenoh.handlers.FifoChannel(4096))

            def drain() -> None:  # reads the bytes as the node side reads the message
                with contextlib.suppress(zenoh.ZError):  # closed with the session
                    for sample in sub.handler:
                        data = sample.payload.to_bytes()
                        if data == warm_cdr:
                            counter.warm.set()
                        elif len(data):
                            counter.hit()

            threading.Thread(target=drain, daemon=True).start()
            return lambda flag, timeout: flag.future.wait(timeout) and None

        return run_once(pub_mode, kind, n, key, subscribe)
    finally:
        session.close()


def node_run(kind: str, n: int, key: str, how: str) -> float:
    """ros2lite: a node's KEEP_ALL subscription, callbacks run here by `spin()`'s loop
    (how='spin') or by the tutorials' `while ok(): spin_once(node)` (how='spin_once')."""
    import ros2lite
    from ros2lite.context import Context
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.interfaces import get_interface
    from ros2lite.node import Node
    from ros2lite.qos import HistoryPolicy, QoSProfile

    ctx = Context()
    ctx.init([])
    try:
        node = Node('bench_sub', context=ctx, enable_rosout=False)
        qos = QoSProfile(history=HistoryPolicy.KEEP_ALL)

        def subscribe(counter: Counter) -> Callable[[Flag, float], None]:
            if kind == 'string':

                def on_msg(msg: Any) -> None:
                    if msg.data == WARMUP:
                        counter.warm.set()
                    else:
                        counter.hit()

                node.create_subscription(get_interface(STRING), 'bench_chatter', on_msg, qos)
            else:

                def on_msg(msg: Any) -> None:
                    if msg.encoding == WARMUP:
                        counter.warm.set()
                    elif len(msg.data):
                        counter.hit()

                node.create_subscription(get_interface(IMAGE), 'bench_image', on_msg, qos)
            if how == 'spin':
                ex = SingleThreadedExecutor(context=ctx)
                ex.add_node(node)
                return lambda flag, timeout: ex.spin_until_future_complete(
                    flag.future, timeout_sec=timeout
                )

            def spin_once_loop(flag: Flag, timeout: float) -> None:
                deadline = time.monotonic() + timeout
                spin_once = ros2lite.spin_once
                while ros2lite.ok(context=ctx) and not flag.is_set():
                    spin_once(node, timeout_sec=0.1)
                    if time.monotonic() > deadline:
                        return

            return spin_once_loop

        return run_once('node', kind, n, key, subscribe)
    finally:
        ctx.shutdown()


def _serialized_warmup(type_name: str) -> bytes:
    from ros2lite.interfaces import get_interface, serialize

    cls = get_interface(type_name)
    return serialize(cls(data=WARMUP) if type_name == STRING else cls(encoding=WARMUP))


def bench_node_throughput() -> None:
    """std_msgs/String: raw, raw + attachment, node with spin() and with spin_once loops."""
    with private_router():
        key = _key(STRING, '/bench_chatter')
        warm = _serialized_warmup(STRING)
        rates: dict[str, list[float]] = {'raw': [], 'rawatt': [], 'spin': [], 'spin_once': []}
        for _ in range(RUNS):  # interleaved, so drifting machine load hits all alike
            rates['raw'].append(raw_run(key, warm, 'string', N_MESSAGES))
            rates['spin'].append(node_run('string', N_MESSAGES, key, 'spin'))
            rates['rawatt'].append(raw_run(key, warm, 'string', N_MESSAGES, 'rawatt'))
            rates['spin_once'].append(node_run('string', N_MESSAGES, key, 'spin_once'))
    med = {k: statistics.median(v) for k, v in rates.items()}
    if VERBOSE:
        for k, v in rates.items():
            print(f'  {k}: {[round(r) for r in v]}', file=sys.stderr)
    base = med['raw']
    report('node_pubsub_string', med['spin'], 'msg/s', med['spin'] / base)
    report('node_pubsub_string_spin_once', med['spin_once'], 'msg/s', med['spin_once'] / base)
    report('node_pubsub_string_raw_zenoh', base, 'msg/s', 1.0)
    report('node_pubsub_string_raw_attachment', med['rawatt'], 'msg/s', med['rawatt'] / base)


def bench_node_image() -> None:
    """1 MiB sensor_msgs/Image, node (spin) against raw."""
    from ros2lite.interfaces import get_interface, serialize

    image = get_interface(IMAGE)(height=512, width=512, encoding='rgba8', step=2048)
    image.data = bytes(1 << 20)
    nbytes = len(serialize(image))
    with private_router():
        key = _key(IMAGE, '/bench_image')
        warm = _serialized_warmup(IMAGE)
        raw: list[float] = []
        ours: list[float] = []
        for _ in range(RUNS):
            raw.append(raw_run(key, warm, 'image', N_IMAGES))
            ours.append(node_run('image', N_IMAGES, key, 'spin'))
    if VERBOSE:
        print(f'  raw {[round(r) for r in raw]} node {[round(r) for r in ours]}', file=sys.stderr)
    r, b = statistics.median(ours), statistics.median(raw)
    report('node_pubsub_image_1mib', r * nbytes / 1e6, 'MB/s', r / b)
    report('node_pubsub_image_1mib_raw_zenoh', b * nbytes / 1e6, 'MB/s', 1.0)


def _ping_pong(mode: str) -> list[float]:
    """Round-trip times (s) of N_PINGS pings through an echo child of `mode`."""
    from ros2lite.interfaces import get_interface, serialize

    String = get_interface(STRING)
    ping_key, pong_key = _key(STRING, '/bench_ping'), _key(STRING, '/bench_pong')
    with ready_child(ECHO, mode, ping_key, pong_key):
        if mode == 'node':
            return _node_pinger()
        return _raw_pinger(ping_key, pong_key, serialize(String(data='ping')))


def _raw_pinger(ping_key: str, pong_key: str, cdr: bytes) -> list[float]:
    import zenoh

    from ros2lite.daemon.security import session_security
    from ros2lite.transport.config import node_session_mode
    from ros2lite.transport.open import open_session

    security = session_security()  # as nodes have it (a secured graph too)
    session = open_session(mode=node_session_mode(security=security), security=security)
    try:
        sub = session.declare_subscriber(pong_key, zenoh.handlers.FifoChannel(64))
        pub = session.declare_publisher(ping_key)
        pongs, put = sub.handler, pub.put
        deadline = time.monotonic() + 10
        while pongs.try_recv() is None:  # until the echo is reachable both ways
            if time.monotonic() > deadline:
                raise RuntimeError('the echo never answered')
            put(cdr)
            time.sleep(0.01)
        time.sleep(0.05)
        while pongs.try_recv() is not None:
            pass
        times = []
        clock = time.perf_counter
        for i in range(N_PINGS + 100):
            t0 = clock()
            put(cdr)
            pongs.recv()
            if i >= 100:
                times.append(clock() - t0)
        return times
    finally:
        session.close()


def _node_pinger() -> list[float]:
    from ros2lite.context import Context
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.interfaces import get_interface
    from ros2lite.node import Node

    String = get_interface(STRING)
    ctx = Context()
    ctx.init([])
    try:
        node = Node('bench_pinger', context=ctx, enable_rosout=False)
        ex = SingleThreadedExecutor(context=ctx)
        ex.add_node(node)
        pub = node.create_publisher(String, 'bench_ping', 10)
        ping = String(data='ping')
        reached = Flag()
        times: list[float] = []
        clock = time.perf_counter
        done = Flag()
        sent = [0.0]
        measuring = [False]

        def on_pong(_msg: Any) -> None:
            if not measuring[0]:
                reached.set()  # the echo is reachable both ways
                return
            times.append(clock() - sent[0])
            if len(times) == N_PINGS + 100:
                done.set()
            else:
                sent[0] = clock()
                pub.publish(ping)

        node.create_subscription(String, 'bench_pong', on_pong, 10)
        deadline = time.monotonic() + 10
        while not reached.is_set():
            if time.monotonic() > deadline:
                raise RuntimeError('the echo never answered')
            pub.publish(ping)
            ex.spin_until_future_complete(reached.future, timeout_sec=0.01)
        ex.spin_until_future_complete(Flag().future, timeout_sec=0.05)  # late pongs
        measuring[0] = True
        sent[0] = clock()
        pub.publish(ping)
        ex.spin_until_future_complete(done.future, timeout_sec=60)
        if not done.is_set():
            raise RuntimeError(f'latency run stalled after {len(times)} pongs')
        return times[100:]
    finally:
        ctx.shutdown()


def bench_node_latency() -> None:
    """Ping-pong round trips, node against raw: p50 and p99."""

    def pct(times: list[float], q: float) -> float:
        s = sorted(times)
        return s[min(len(s) - 1, int(len(s) * q))]

    with private_router():
        raw = {'p50': [], 'p99': []}  # type: dict[str, list[float]]
        ours = {'p50': [], 'p99': []}  # type: dict[str, list[float]]
        for _ in range(RUNS):
            for side, mode in ((raw, 'raw'), (ours, 'node')):
                times = _ping_pong(mode)
                side['p50'].append(pct(times, 0.5) * 1e6)
                side['p99'].append(pct(times, 0.99) * 1e6)
                if VERBOSE:
                    print(
                        f'  {mode}: p50 {side["p50"][-1]:.0f} us, p99 {side["p99"][-1]:.0f} us',
                        file=sys.stderr,
                    )
    for q in ('p50', 'p99'):
        r, b = statistics.median(ours[q]), statistics.median(raw[q])
        report(f'node_latency_{q}', r, 'us', r / b)
        report(f'node_latency_{q}_raw_zenoh', b, 'us', 1.0)


BENCHES = {
    'node': bench_node_throughput,
    'node_image': bench_node_image,
    'node_latency': bench_node_latency,
}
