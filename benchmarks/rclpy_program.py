"""The rclpy program that `bench_vs_rclpy.py` runs on real rclpy and on ros2lite alike.

It uses rclpy's public API only and never imports ros2lite: on the ros2lite side it finds
`rclpy` through what `ros2lite env` puts on PYTHONPATH, as a user's program would. The role is
argv[1]; every role that measures prints exactly one line `RESULT <role> key=value ...`, and
roles that others wait for print `ready` once they are set up.

    sub SIZE SECS         count messages on /vs_flood for SECS s after the first one, spun by
                          spin_until_future_complete (what spin() does); rate=msg/s mbps=MB/s
    sub_once SIZE SECS    the same, spun the tutorials' way: spin_once in a while loop
    pub SIZE SECS         publish as fast as publish() returns for SECS+1 s, after the
                          subscriber matched and a warm-up pause
    echo                  publish every /vs_ping message back on /vs_pong (spin)
    ping N                N round trips, one message in flight, spin_once(timeout_sec=0.1)
                          until the answer is in; p50/p99 in µs
    server                std_srvs/SetBool server on /vs_set_bool (spin)
    client N              N calls, each call_async + spin_until_future_complete; p50/p99 µs
    client_sync N         N Client.call()s while a SingleThreadedExecutor spins on a thread
    startup_sub           wait for one message on /vs_startup; at=its arrival (monotonic s)
    startup               init, publisher, wait for the match, publish once, leave

SIZE up to 256 bytes is a std_msgs/String of that length, above a mono8 sensor_msgs/Image of
SIZE bytes. Every wait is bounded, so a silent peer ends a role instead of hanging it.
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Callable
from typing import Any

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy

QOS = QoSProfile(
    history=HistoryPolicy.KEEP_LAST, depth=1000, reliability=ReliabilityPolicy.RELIABLE
)
WARM_PINGS = 100  # round trips and calls left out of the percentiles
WARM_CALLS = 50
MATCH_TIMEOUT = 10.0


def say(role: str, **fields: object) -> None:
    print('RESULT', role, *(f'{k}={v}' for k, v in fields.items()), flush=True)


def ready() -> None:
    print('ready', flush=True)


def percentiles(samples: list[float]) -> dict[str, str]:
    """p50 and p99 of `samples` (seconds) in whole µs; empty when nothing was measured."""
    if not samples:
        return {}
    ordered = sorted(samples)

    def at(q: float) -> str:
        return f'{ordered[min(len(ordered) - 1, int(q * len(ordered)))] * 1e6:.0f}'

    return {'p50': at(0.5), 'p99': at(0.99)}


def message_kind(size: int) -> tuple[Any, Callable[[], Any]]:
    """The message type for `size` bytes of payload and a maker of one such message."""
    if size <= 256:
        from std_msgs.msg import String

        return String, lambda: String(data='x' * size)
    from sensor_msgs.msg import Image

    pixels = bytes(size)

    def image() -> Any:
        msg = Image()
        msg.height, msg.width, msg.step, msg.encoding = 1, size, size, 'mono8'
        msg.data = pixels
        return msg

    return Image, image


def spin_a_little(node: Node, until: Callable[[], bool], timeout: float) -> None:
    """spin_once until `until()` holds or `timeout` s passed."""
    deadline = time.monotonic() + timeout
    while not until() and time.monotonic() < deadline:
        rclpy.spin_once(node, timeout_sec=0.05)


def run_sub(node: Node, role: str, size: int, secs: float) -> None:
    from rclpy.task import Future

    kind, _ = message_kind(size)
    count = 0
    first = last = 0.0
    finished = Future()

    def on_message(_msg: Any) -> None:
        nonlocal count, first, last
        now = time.perf_counter()
        if not count:
            first = now
        count += 1
        last = now
        if now - first >= secs and not finished.done():
            finished.set_result(True)

    def publisher_gone() -> None:  # it stopped early: what arrived is the answer
        if count and time.perf_counter() - last > 2.0 and not finished.done():
            finished.set_result(False)

    node.create_subscription(kind, 'vs_flood', on_message, QOS)
    node.create_timer(0.5, publisher_gone)
    ready()
    if role == 'sub':
        rclpy.spin_until_future_complete(node, finished, timeout_sec=60.0)
    else:
        spin_a_little(node, finished.done, 60.0)
    span = last - first
    if count < 2 or span <= 0:
        say(role, msgs=count)
        return
    per_second = (count - 1) / span
    say(role, msgs=count, rate=f'{per_second:.0f}', mbps=f'{per_second * size / 1e6:.1f}')


def run_pub(node: Node, size: int, secs: float) -> None:
    kind, make = message_kind(size)
    pub = node.create_publisher(kind, 'vs_flood', QOS)
    spin_a_little(node, lambda: pub.get_subscription_count() > 0, MATCH_TIMEOUT)
    time.sleep(1.5)  # both sides settle (discovery traffic, first allocations)
    msg = make()
    sent = 0
    start = time.perf_counter()
    while time.perf_counter() - start < secs + 1.0:
        pub.publish(msg)
        sent += 1
    say('pub', sent=sent, rate=f'{sent / (time.perf_counter() - start):.0f}')
    time.sleep(1.0)  # reliable delivery of the tail before the node goes


def run_echo(node: Node) -> None:
    from std_msgs.msg import String

    back = node.create_publisher(String, 'vs_pong', QOS)
    node.create_subscription(String, 'vs_ping', back.publish, QOS)
    ready()
    rclpy.spin(node)


def run_ping(node: Node, n: int) -> None:
    from std_msgs.msg import String

    arrivals: list[float] = []
    ping = node.create_publisher(String, 'vs_ping', QOS)
    node.create_subscription(
        String, 'vs_pong', lambda _m: arrivals.append(time.perf_counter()), QOS
    )
    spin_a_little(
        node,
        lambda: ping.get_subscription_count() > 0 and node.count_publishers('vs_pong') > 0,
        MATCH_TIMEOUT,
    )
    time.sleep(1.0)
    msg = String(data='x' * 16)
    trips: list[float] = []
    for i in range(n + WARM_PINGS):
        heard = len(arrivals)
        sent = time.perf_counter()
        ping.publish(msg)
        give_up = sent + 1.0
        while len(arrivals) == heard and time.perf_counter() < give_up:
            rclpy.spin_once(node, timeout_sec=0.1)
        if len(arrivals) > heard and i >= WARM_PINGS:
            trips.append(arrivals[-1] - sent)
    say('ping', n=len(trips), **percentiles(trips))


def run_server(node: Node) -> None:
    from std_srvs.srv import SetBool

    def answer(request: Any, response: Any) -> Any:
        response.success = request.data
        response.message = 'set'
        return response

    node.create_service(SetBool, 'vs_set_bool', answer)
    ready()
    rclpy.spin(node)


def run_client(node: Node, role: str, n: int) -> None:
    from std_srvs.srv import SetBool

    client = node.create_client(SetBool, 'vs_set_bool')
    if not client.wait_for_service(timeout_sec=MATCH_TIMEOUT):
        say(role, n=0)
        return
    time.sleep(0.5)
    executor = None
    if role == 'client_sync':  # call() blocks; an executor elsewhere delivers the answer
        from rclpy.executors import SingleThreadedExecutor

        executor = SingleThreadedExecutor()
        executor.add_node(node)
        threading.Thread(target=executor.spin, daemon=True).start()
    request = SetBool.Request(data=True)
    calls: list[float] = []
    for i in range(n + WARM_CALLS):
        start = time.perf_counter()
        if executor is None:
            future = client.call_async(request)
            rclpy.spin_until_future_complete(node, future, timeout_sec=5.0)
            if not future.done():
                break
        else:
            client.call(request, timeout_sec=5.0)
        if i >= WARM_CALLS:
            calls.append(time.perf_counter() - start)
    say(role, n=len(calls), **percentiles(calls))
    if executor is not None:
        executor.shutdown(timeout_sec=1.0)


def run_startup_sub(node: Node) -> None:
    from std_msgs.msg import String

    arrived: list[float] = []
    node.create_subscription(String, 'vs_startup', lambda _m: arrived.append(time.monotonic()), QOS)
    ready()
    spin_a_little(node, lambda: bool(arrived), 30.0)
    say('startup_sub', got=len(arrived), **({'at': f'{arrived[0]:.6f}'} if arrived else {}))


def run_startup(node: Node) -> None:
    from std_msgs.msg import String

    pub = node.create_publisher(String, 'vs_startup', QOS)
    deadline = time.monotonic() + MATCH_TIMEOUT
    while pub.get_subscription_count() == 0 and time.monotonic() < deadline:
        time.sleep(0.005)
    pub.publish(String(data='up'))
    say('startup', matched=pub.get_subscription_count())
    time.sleep(0.1)  # let the one reliable message leave before the node does


def main(argv: list[str]) -> None:
    role, args = argv[1], argv[2:]
    rclpy.init()
    node = Node(f'vs_{role}')
    try:
        if role in ('sub', 'sub_once'):
            run_sub(node, role, int(args[0]), float(args[1]))
        elif role == 'pub':
            run_pub(node, int(args[0]), float(args[1]))
        elif role == 'echo':
            run_echo(node)
        elif role == 'ping':
            run_ping(node, int(args[0]))
        elif role == 'server':
            run_server(node)
        elif role in ('client', 'client_sync'):
            run_client(node, role, int(args[0]))
        elif role == 'startup_sub':
            run_startup_sub(node)
        elif role == 'startup':
            run_startup(node)
        else:
            raise SystemExit(f'unknown role {role!r}')
    except (KeyboardInterrupt, ExternalShutdownException):
        pass  # the caller's SIGINT/SIGTERM ends the serving roles
    finally:
        node.destroy_node()
        rclpy.try_shutdown()


if __name__ == '__main__':
    main(sys.argv)
