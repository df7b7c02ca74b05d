"""Hostile samples from a bare zenoh peer: garbage, empty, truncated and huge-length payloads
are dropped and reported once per publisher; subscribers, /clock and `topic echo` go on."""

from __future__ import annotations

import struct
import threading
import time
from typing import Any

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from ros2lite.runtime.bad_samples import BadSamples, describe_publisher
from tests.spinning import queued, spin_until, wait_for_route, wait_until

STRING_HASH = 'RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18'
CLOCK_TYPE = 'rosgraph_msgs::msg::dds_::Clock_'
CLOCK_HASH = 'RIHS01_692f7a66e93a3c83e71765d033b60349ba68023a8c689a79e48078bcb5c58564'
# what a hostile or broken peer sends as a std_msgs/String
HOSTILE = [
    b'',  # empty
    b'\x00\x01',  # shorter than the CDR header
    b'\x00\x01\x00\x00\x10\x00\x00\x00abc',  # truncated
    b'\x00\x01\x00\x00\xff\xff\xff\xffabc',  # a 4 GiB length
    b'\x07\x07\x07\x07garbage!',  # not CDR at all
]


def cdr_string(text: str) -> bytes:
    raw = text.encode() + b'\x00'
    return b'\x00\x01\x00\x00' + struct.pack('<I', len(raw)) + raw


def attachment(seq: int, gid: bytes) -> bytes:
    return struct.pack('<qqB', seq, time.time_ns(), 16) + gid


def gid(n: int) -> bytes:
    return bytes([n]) * 16


def test_reports_once_per_publisher_rate_limited_and_bounded() -> None:
    now = [0.0]
    warnings: list[str] = []
    bad = BadSamples(
        '/t', 'std_msgs/msg/String', warnings.append, max_publishers=3, clock=lambda: now[0]
    )
    for _ in range(5):
        bad.add(gid(1), 'truncated', 3)
    assert bad.total == 5 and bad.count(gid(1)) == 5 and len(warnings) == 1
    assert warnings[0].startswith(
        f"dropped a sample on '/t' from {describe_publisher(gid(1))}: not a valid "
        'std_msgs/msg/String (3 bytes: truncated)'
    )
    for n in range(2, 10):  # new publishers within the same second: held back
        bad.add(gid(n), 'x', 1)
    assert len(warnings) == 1 and bad.publishers == 3
    now[0] = 1.5
    bad.add(gid(42), 'x', 1)
    assert len(warnings) == 2 and warnings[1].endswith(
        '8 other publisher(s) sent bad samples since the last warning'
    )
    assert bad.total == 14 and bad.publishers == 3


def _publish(session: Any, key: str, payloads: list[tuple[bytes, bytes]]) -> None:
    pub = session.declare_publisher(key)
    try:
        for payload, att in payloads:
            pub.put(payload, attachment=att)
    finally:
        pub.undeclare()


def test_a_subscriber_survives_every_hostile_sample(
    ros_context: Any, alien_session: Any, capfd: Any
) -> None:
    node = Node('victim', context=ros_context)
    heard: list[str] = []
    sub = node.create_subscription(
        'std_msgs/msg/String', '/hostile', lambda m: heard.append(m.data), 100
    )
    key = f'{ros_context.domain_id}/hostile/std_msgs::msg::dds_::String_/{STRING_HASH}'
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    # the router must route to the subscription before anything is sent
    wait_for_route(alien_session, node, '/hostile')
    samples = [(p, attachment(i, gid(1))) for i, p in enumerate(HOSTILE)]
    samples += [(p, attachment(i, gid(2))) for i, p in enumerate(HOSTILE)]
    samples.append((cdr_string('still here'), attachment(99, gid(3))))
    _publish(alien_session, key, samples)
    spin_until(executor, lambda: heard == ['still here'], timeout=15)
    assert sub.bad_samples is not None and sub.bad_samples.total == 2 * len(HOSTILE)
    err = capfd.readouterr().err
    warned = [line for line in err.splitlines() if "dropped a sample on '/hostile'" in line]
    assert len(warned) == 1, err  # publisher 2 came within the rate limit: counted
    assert describe_publisher(gid(1)) in warned[0]
    # take() drops them too (async callbacks and rclpy's take go through it)
    _publish(alien_session, key, [(b'junk', attachment(1, gid(4)))])
    _publish(alien_session, key, [(cdr_string('taken'), attachment(2, gid(4)))])
    wait_until(lambda: len(queued(sub)) == 2)
    msg, info = sub.take()  # type: ignore[misc]
    assert msg.data == 'taken' and info.publisher_gid == gid(4)
    executor.shutdown()


def test_a_bad_clock_sample_does_not_stop_sim_time(ros_context: Any, alien_session: Any) -> None:
    from ros2lite.parameter import Parameter

    node = Node(
        'sim_victim',
        context=ros_context,
        parameter_overrides=[Parameter('use_sim_time', value=True)],
    )
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    wait_for_route(alien_session, node, '/clock')
    key = f'{ros_context.domain_id}/clock/{CLOCK_TYPE}/{CLOCK_HASH}'
    good = b'\x00\x01\x00\x00' + struct.pack('<iI', 42, 7)
    _publish(
        alien_session,
        key,
        [(b'\x00\x01\x00', attachment(1, gid(5))), (good, attachment(2, gid(5)))],
    )
    spin_until(executor, lambda: node.get_clock().now().nanoseconds == 42_000_000_007, 15)
    executor.shutdown()


def test_listener_demo_and_topic_echo_go_on(processes: Any, alien_session: Any) -> None:
    import os

    listener = processes.cli('run', 'demo_nodes_py', 'listener')
    echo = processes.cli('topic', 'echo', '/chatter', 'std_msgs/msg/String', '-i')
    domain = os.environ['ROS_DOMAIN_ID']
    key = f'{domain}/chatter/std_msgs::msg::dds_::String_/{STRING_HASH}'
    from ros2lite.graph import EntityKind

    def subscribers() -> int:
        from ros2lite.tools.connection import Connection

        with Connection() as conn:
            return sum(
                1
                for e in conn.entities()
                if e.kind == EntityKind.SUBSCRIPTION and e.topic_name == '/chatter'
            )

    wait_until(lambda: subscribers() >= 2, timeout=30, interval=0.3)
    time.sleep(0.5)  # a token is declared just before its subscriber starts listening
    payloads = [(p, attachment(i, gid(7))) for i, p in enumerate(HOSTILE)]
    payloads.append((cdr_string('hello after garbage'), attachment(10, gid(7))))
    lines: list[str] = []
    reader = threading.Thread(target=lambda: lines.extend(iter(echo.stdout.readline, '')))
    reader.start()
    deadline = time.monotonic() + 30
    while not any('hello after garbage' in ln for ln in lines):
        assert time.monotonic() < deadline, lines
        _publish(alien_session, key, payloads)
        time.sleep(0.5)
    assert listener.poll() is None and echo.poll() is None
    out, err = processes.stop(listener)
    assert 'I heard: [hello after garbage]' in out + err
    assert err.count("dropped a sample on '/chatter'") == 1, err
    processes.stop(echo)
    reader.join(timeout=5)
    text = ''.join(lines)
    assert '# dropped: not a valid std_msgs/msg/String from publisher 07.07' in text
    assert 'data: hello after garbage' in text


def test_a_callbacks_own_value_error_still_reaches_the_caller(
    ros_context: Any, alien_session: Any
) -> None:
    import pytest

    node = Node('raiser', context=ros_context)

    def callback(msg: Any) -> None:
        raise ValueError(f'user bug on {msg.data}')

    sub = node.create_subscription('std_msgs/msg/String', '/raiser', callback, 100)
    wait_for_route(alien_session, node, '/raiser')
    key = f'{ros_context.domain_id}/raiser/std_msgs::msg::dds_::String_/{STRING_HASH}'
    _publish(
        alien_session,
        key,
        [(b'junk', attachment(1, gid(9))), (cdr_string('x'), attachment(2, gid(9)))],
    )
    wait_until(lambda: len(queued(sub)) == 2)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    with pytest.raises(ValueError, match='user bug on x'):
        executor.spin_once(timeout_sec=5)
        executor.spin_once(timeout_sec=5)
    assert sub.bad_samples is not None and sub.bad_samples.total == 1
    executor.shutdown()


def test_a_message_and_info_callback_survives_hostile_samples(
    ros_context: Any, alien_session: Any
) -> None:
    """`callback(msg, info)` takes the slower loop: bad samples are dropped there too, and the
    good one arrives with its publisher's info."""
    from ros2lite.subscription import MessageInfo

    node = Node('info_victim', context=ros_context)
    heard: list[tuple[str, bytes]] = []

    def callback(msg: Any, info: MessageInfo) -> None:
        heard.append((msg.data, info.publisher_gid))

    sub = node.create_subscription('std_msgs/msg/String', '/hostile_info', callback, 100)
    wait_for_route(alien_session, node, '/hostile_info')
    key = f'{ros_context.domain_id}/hostile_info/std_msgs::msg::dds_::String_/{STRING_HASH}'
    samples = [(p, attachment(i, gid(6))) for i, p in enumerate(HOSTILE)]
    samples.append((cdr_string('with info'), attachment(99, gid(7))))
    _publish(alien_session, key, samples)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    spin_until(executor, lambda: bool(heard), timeout=15)
    assert heard == [('with info', gid(7))]
    assert sub.bad_samples is not None and sub.bad_samples.total == len(HOSTILE)
    executor.shutdown()
