"""`topic pub` against live subscriptions: loop output, counts, waiting, stamps and errors."""

from __future__ import annotations

import re
import time
from collections.abc import Callable
from typing import Any

from ...conftest import wait_until
from ..conftest import Result, run_process
from .conftest import graph, has_endpoint

STRING = 'std_msgs/msg/String'


def test_once_publishes_one_message(
    run: Callable[..., Result], listener: Any, ros_context: Any, topic: str
) -> None:
    heard = listener(topic, STRING)
    wait_until(lambda: has_endpoint(ros_context, topic, 'MS'))
    result = run('topic', 'pub', '-1', topic, STRING, 'data: hello')
    assert result.code == 0, result.err
    assert result.out == (
        "publisher: beginning loop\npublishing #1: std_msgs.msg.String(data='hello')\n\n"
    )
    wait_until(lambda: heard.messages)
    assert [m.data for m in heard.messages] == ['hello']


def test_times_and_print_every_nth(
    run: Callable[..., Result], listener: Any, ros_context: Any, topic: str
) -> None:
    heard = listener(topic, 'std_msgs/msg/Int32')
    wait_until(lambda: has_endpoint(ros_context, topic, 'MS'))
    started = time.monotonic()
    result = run(
        'topic', 'pub', '-t', '4', '-r', '20', '-p', '2', topic, 'std_msgs/msg/Int32', '{data: 7}'
    )
    elapsed = time.monotonic() - started
    assert result.code == 0
    assert result.out == (
        'publisher: beginning loop\n'
        'publishing #2: std_msgs.msg.Int32(data=7)\n\n'
        'publishing #4: std_msgs.msg.Int32(data=7)\n\n'
    )
    assert elapsed >= 3 / 20  # first at once, then one per 1/rate
    wait_until(lambda: len(heard.messages) == 4)
    time.sleep(0.1)
    assert [m.data for m in heard.messages] == [7, 7, 7, 7]


def test_waits_for_matching_subscriptions(
    processes: Any, listener: Any, ros_context: Any, topic: str
) -> None:
    proc = processes.cli('topic', 'pub', '-1', topic, STRING, 'data: late')
    wait_until(lambda: has_endpoint(ros_context, topic, 'MP'))
    time.sleep(1.2)  # long enough for the 1 s reminder
    heard = listener(topic, STRING)
    wait_until(lambda: proc.poll() is not None)
    out, err = processes.stop(proc)
    assert proc.returncode == 0, err
    lines = out.splitlines()
    waiting = 'Waiting for at least 1 matching subscription(s)...'
    assert lines[:2] == [waiting, waiting]
    assert lines[-3:] == [
        'publisher: beginning loop',
        "publishing #1: std_msgs.msg.String(data='late')",
        '',
    ]
    wait_until(lambda: heard.messages)


def test_wait_timeout_error(
    run: Callable[..., Result], listener: Any, ros_context: Any, topic: str
) -> None:
    listener(topic, STRING)
    wait_until(lambda: has_endpoint(ros_context, topic, 'MS'))
    result = run('topic', 'pub', '-w', '2', '--max-wait-time-secs', '0.3', topic, STRING)
    assert result.code == 1
    assert result.out == 'Waiting for at least 2 matching subscription(s)...\n'
    assert result.err == (
        'Timed out waiting for subscribers: Expected 2 subcribers but only got 1 subscribers\n'
    )


def test_max_wait_needs_something_to_wait_for(run: Callable[..., Result], topic: str) -> None:
    result = run('topic', 'pub', '--max-wait-time-secs', '1', topic, STRING)
    assert (result.code, result.out) == (1, '')
    assert result.err == (
        '--max-wait-time-secs option is only effective with '
        '--wait-matching-subscriptions, --once or --times\n'
    )


def test_value_errors(run: Callable[..., Result], topic: str) -> None:
    cases = {
        ('std_msgs/msg/Nope', '{}'): 'The passed message type is invalid',
        (STRING, 'data'): 'The passed value needs to be a dictionary in YAML format',
        (STRING, '[1, 2]'): 'The passed value needs to be a dictionary in YAML format',
        # where the YAML breaks, in the one line
        (STRING, '{data: [1'): 'The passed value needs to be in YAML string or a dictionary: '
        "expected ',' or ']', but got '<stream end>' (line 1, column 10)",
        (STRING, 'data: 1\n  b: 2'): 'The passed value needs to be in YAML string or a '
        'dictionary: mapping values are not allowed here (line 2, column 4)',
        # refused as rclpy's setter refuses it, never truncated to 1
        ('std_msgs/msg/Int32', '{data: 1.5}'): "Failed to populate field: field 'data' is an "
        'integer (int32); 1.5 is not one',
        ('std_msgs/msg/Int32MultiArray', '{data: [1, 2.5]}'): "Failed to populate field: field "
        "'data' is a list of integers (int32[]); 2.5 is not one",
        (STRING, '{nope: 1}'): "Failed to populate field: 'String' object has no attribute 'nope'",
        ('std_msgs/msg/Int8', '{data: 300}'): 'Failed to populate field: The \'data\' field '
        'must be an integer in [-128, 127]',
    }
    for (type_name, values), message in cases.items():
        result = run('topic', 'pub', '-1', '-w', '0', topic, type_name, values)
        assert (result.code, result.err) == (1, message + '\n'), (type_name, values)
        assert 'publishing' not in result.out


def test_header_auto_and_stamp_now_refresh_every_publish(
    run: Callable[..., Result], listener: Any, ros_context: Any, topic: str
) -> None:
    heard = listener(topic, 'geometry_msgs/msg/PointStamped')
    wait_until(lambda: has_endpoint(ros_context, topic, 'MS'))
    before = time.time_ns()
    result = run(
        'topic',
        'pub',
        '-t',
        '2',
        '-r',
        '10',
        '-p',
        '0',
        topic,
        'geometry_msgs/msg/PointStamped',
        '{header: auto, point: {x: 1.5}}',
    )
    after = time.time_ns()
    assert result.code == 0 and result.out == 'publisher: beginning loop\n'
    wait_until(lambda: len(heard.messages) == 2)
    stamps = [m.header.stamp.sec * 10**9 + m.header.stamp.nanosec for m in heard.messages]
    assert before <= stamps[0] < stamps[1] <= after
    assert stamps[1] - stamps[0] >= 0.05e9  # refreshed, a period apart
    assert [(m.header.frame_id, m.point.x) for m in heard.messages] == [('', 1.5)] * 2

    topic2 = topic + '_now'
    heard2 = listener(topic2, 'std_msgs/msg/Header')
    wait_until(lambda: has_endpoint(ros_context, topic2, 'MS'))
    result = run(
        'topic',
        'pub',
        '-1',
        '-p',
        '0',
        topic2,
        'std_msgs/msg/Header',
        '{stamp: now, frame_id: map}',
    )
    wait_until(lambda: heard2.messages)
    msg = heard2.messages[0]
    assert msg.frame_id == 'map' and abs(msg.stamp.sec - time.time()) < 5


def test_stdin_values(listener: Any, ros_context: Any, topic: str) -> None:
    heard = listener(topic, STRING)
    wait_until(lambda: has_endpoint(ros_context, topic, 'MS'))
    result = run_process('topic', 'pub', '-1', '--stdin', topic, STRING, stdin='data: from stdin\n')
    assert result.code == 0, result.err
    assert "std_msgs.msg.String(data='from stdin')" in result.out
    wait_until(lambda: heard.messages)


def test_once_and_times_conflict(run: Callable[..., Result], topic: str) -> None:
    result = run('topic', 'pub', '-1', '-t', '3', topic, STRING)
    assert result.code == 2


def test_default_loop_publishes_at_rate_with_node_name_and_qos(
    processes: Any, listener: Any, ros_context: Any, topic: str
) -> None:
    heard = listener(topic, STRING)
    proc = processes.cli(
        'topic',
        'pub',
        '-n',
        'my_pub',
        '-r',
        '20',
        '--qos-reliability',
        'best_effort',
        topic,
        STRING,
        'data: loop',
    )
    wait_until(lambda: len(heard.messages) >= 5)
    # one liveliness query can miss a token a just-started peer declared: ask until it shows
    pubs = wait_until(
        lambda: [e for e in graph(ros_context) if e.kind.value == 'MP' and e.topic_name == topic]
    )
    assert [e.node_name for e in pubs] == ['my_pub']
    assert pubs[0].qos is not None and pubs[0].qos.reliability.name == 'BEST_EFFORT'
    out, _ = processes.stop(proc)
    numbers = [int(n) for n in re.findall(r'publishing #(\d+): ', out)]
    assert numbers[:5] == [1, 2, 3, 4, 5]
    assert out.startswith('publisher: beginning loop\n')  # no wait without -w/-1/-t
