"""The bundled Fibonacci action server and client as real processes, started with
`ros2lite run`: their graph presence and their log lines, end to end."""

from __future__ import annotations

import re
import time
from typing import Any

from ros2lite.action import get_action_names_and_types
from ros2lite.action.graph import get_action_server_names_and_types_by_node
from ros2lite.node import Node
from tests.bundled.test_demo_nodes_py import log_line

FIB = 'action_tutorials_interfaces/action/Fibonacci'


def test_fibonacci_server_and_client(ros_context: Any, processes: Any) -> None:
    server = processes.cli('run', 'action_tutorials_py', 'fibonacci_action_server')
    observer = Node('action_observer', context=ros_context)
    deadline = time.monotonic() + 15
    while ('/fibonacci', [FIB]) not in get_action_names_and_types(observer):
        assert time.monotonic() < deadline, get_action_names_and_types(observer)
        time.sleep(0.05)
    assert get_action_server_names_and_types_by_node(observer, 'fibonacci_action_server', '/') == [
        ('/fibonacci', [FIB])
    ]

    client = processes.cli('run', 'action_tutorials_py', 'fibonacci_action_client')
    out, err = client.communicate(timeout=40)
    assert client.returncode == 0, err
    name = 'fibonacci_action_client'
    expected = [
        'Waiting for action server...',
        'Sending goal request...',
        'Goal accepted :)',
        *[
            f"Received feedback: array('i', {seq})"
            for seq in (
                [0, 1, 1],
                [0, 1, 1, 2],
                [0, 1, 1, 2, 3],
                [0, 1, 1, 2, 3, 5],
                [0, 1, 1, 2, 3, 5, 8],
                [0, 1, 1, 2, 3, 5, 8, 13],
                [0, 1, 1, 2, 3, 5, 8, 13, 21],
                [0, 1, 1, 2, 3, 5, 8, 13, 21, 34],
                [0, 1, 1, 2, 3, 5, 8, 13, 21, 34, 55],
            )
        ],
        "Goal succeeded! Result: array('i', [0, 1, 1, 2, 3, 5, 8, 13, 21, 34, 55])",
    ]
    lines = err.splitlines()
    assert len(lines) == len(expected), err
    for line, text in zip(lines, expected, strict=True):
        assert re.fullmatch(log_line(name, re.escape(text)), line), (line, text)
    assert out == ''

    _, server_err = processes.stop(server)
    assert server.returncode == 0 and 'Traceback' not in server_err
    server_lines = server_err.splitlines()
    name = 'fibonacci_action_server'
    for line, text in zip(
        server_lines,
        [
            'Received goal request',
            'Executing goal...',
            "Publishing feedback: array('i', [0, 1, 1])",
        ],
        strict=False,
    ):
        assert re.fullmatch(log_line(name, re.escape(text)), line), (line, text)
    assert re.fullmatch(
        log_line(
            name, re.escape("Returning result: array('i', [0, 1, 1, 2, 3, 5, 8, 13, 21, 34, 55])")
        ),
        server_lines[-1],
    ), server_err
