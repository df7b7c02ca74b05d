"""`action echo` as a real process: an introspected action server's three services, its
feedback and its status, each printed under its interface name as Kilted prints them."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from typing import Any

import pytest
import yaml

from ros2lite.action import ActionClient, ActionServer
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from ros2lite.qos import qos_profile_system_default
from ros2lite.service_introspection import ServiceIntrospectionState
from tests.spinning import wait_until

Fibonacci = get_interface('example_interfaces/action/Fibonacci')


@pytest.fixture
def fib(ros_context: Any) -> Iterator[tuple[Node, ActionServer, ActionClient]]:
    def execute(goal: Any) -> Any:
        goal.publish_feedback(Fibonacci.Feedback(sequence=[0, 1]))
        goal.succeed()
        return Fibonacci.Result(sequence=[0, 1, 1])

    node = Node('echo_fib', context=ros_context, enable_rosout=False)
    server = ActionServer(node, Fibonacci, '/echo_fib', execute)
    client = ActionClient(node, Fibonacci, '/echo_fib')
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    thread = threading.Thread(target=executor.spin, daemon=True)
    thread.start()
    yield node, server, client
    executor.shutdown()
    thread.join(timeout=5)
    node.destroy_node()


def test_action_echo(fib: tuple[Node, ActionServer, ActionClient], processes: Any) -> None:
    node, server, client = fib
    server.configure_introspection(
        node.get_clock(), qos_profile_system_default, ServiceIntrospectionState.CONTENTS
    )
    echo = processes.cli(
        'action', 'echo', '/echo_fib', '-i', 'goal_service|FEEDBACK_TOPIC|RESULT_SERVICE'
    )
    lines: list[str] = []
    reader = threading.Thread(target=lambda: lines.extend(echo.stdout), daemon=True)
    reader.start()
    # the echo's subscriptions (the feedback one besides our client's)
    wanted = {
        '/echo_fib/_action/send_goal/_service_event': 1,
        '/echo_fib/_action/get_result/_service_event': 1,
        '/echo_fib/_action/feedback': 2,
    }
    wait_until(lambda: all(node.count_subscribers(t) == n for t, n in wanted.items()), timeout=20)
    # status was not asked for: only our client listens to it
    assert node.count_subscribers('/echo_fib/_action/status') == 1
    assert client.wait_for_server(timeout_sec=10)
    sent = client.send_goal_async(Fibonacci.Goal(order=2))
    wait_until(lambda: sent.done(), timeout=10)
    result = sent.result().get_result_async()
    wait_until(lambda: result.done(), timeout=10)
    assert list(result.result().result.sequence) == [0, 1, 1]
    wait_until(lambda: ''.join(lines).count('---\n') == 5, timeout=20)
    processes.stop(echo)
    reader.join(timeout=5)

    blocks = [b for b in ''.join(lines).split('---\n') if b]
    seen = []
    for block in blocks:
        head, _, body = block.partition('\n')
        interface = head.removeprefix('interface: ')
        message = yaml.safe_load(body)
        seen.append((interface, message.get('info', {}).get('event_type')))
        if interface == 'FEEDBACK_TOPIC':
            assert message['feedback'] == {'sequence': [0, 1]}
        if (interface, seen[-1][1]) == ('RESULT_SERVICE', 'RESPONSE_SENT'):
            assert message['response'][0]['result'] == {'sequence': [0, 1, 1]}
    assert sorted(seen, key=str) == sorted(
        [
            ('GOAL_SERVICE', 'REQUEST_RECEIVED'),
            ('GOAL_SERVICE', 'RESPONSE_SENT'),
            ('FEEDBACK_TOPIC', None),
            ('RESULT_SERVICE', 'REQUEST_RECEIVED'),
            ('RESULT_SERVICE', 'RESPONSE_SENT'),
        ],
        key=str,
    )


def test_action_echo_bad_interface(run: Any) -> None:
    bad = run('action', 'echo', '/echo_fib', 'example_interfaces/action/Fibonacci', '-i', 'NOPE')
    assert (bad.code, bad.err) == (1, '"NOPE" is incorrect interface name.\n')
    empty = run('action', 'echo', '/echo_fib', '-i', '')
    assert (empty.code, empty.err) == (1, 'Input action interface name is empty.\n')
