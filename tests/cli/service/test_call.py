"""`service call`: ros2cli's output, rates, errors and exit statuses (as a real process)."""

from __future__ import annotations

import signal
import subprocess
import sys
import time
from typing import Any

from tests.cli.conftest import run_process

REQUEST = 'requester: making request: example_interfaces.srv.AddTwoInts_Request(a=2, b=40)\n\n'
RESPONSE = 'response:\nexample_interfaces.srv.AddTwoInts_Response(sum=42)\n\n'


def test_call_prints_request_and_response(adder: Any) -> None:
    result = run_process(
        'service', 'call', '/add_two_ints', 'example_interfaces/srv/AddTwoInts', '{a: 2, b: 40}'
    )
    assert (result.code, result.out, result.err) == (0, REQUEST + RESPONSE, '')
    short = run_process(
        'service', 'call', 'math/add', 'example_interfaces/AddTwoInts', '{a: 2, b: 40}'
    )
    assert short.out == REQUEST + RESPONSE
    stdin = run_process(
        'service',
        'call',
        '/math/add',
        'example_interfaces/AddTwoInts',
        '--stdin',
        stdin='a: 2\nb: 40\n',
    )
    assert stdin.out == REQUEST + RESPONSE


def test_call_at_a_rate_until_ctrl_c(adder: Any) -> None:
    proc = subprocess.Popen(
        [
            sys.executable,
            '-m',
            'ros2lite',
            'service',
            'call',
            '/math/add',
            'example_interfaces/srv/AddTwoInts',
            '{a: 2, b: 40}',
            '-r',
            '20',
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    assert proc.stdout is not None
    lines = [proc.stdout.readline() for _ in range(3 * 5)]  # three calls, five lines each
    proc.send_signal(signal.SIGINT)
    _out, err = proc.communicate(timeout=10)
    assert ''.join(lines) == (REQUEST + RESPONSE) * 3
    assert proc.returncode == 2 and 'Traceback' not in err


def test_call_errors(adder: Any) -> None:
    cases = [
        (('/math/add', 'foo/Bar'), 'The passed service type is invalid'),
        (('/math/add', 'std_msgs/msg/String'), 'The passed type is not a service'),
        (
            ('/math/add', 'example_interfaces/AddTwoInts', '{a: x}'),
            "Failed to populate field: invalid literal for int() with base 10: 'x'",
        ),
        (
            ('/math/add', 'example_interfaces/AddTwoInts', '{a: 1.5, b: 2}'),
            "Failed to populate field: field 'a' is an integer (int64); 1.5 is not one",
        ),
        (
            ('/math/add', 'example_interfaces/AddTwoInts', '{a: 1, b: [2'),
            'The passed value needs to be in YAML string or a dictionary: '
            "expected ',' or ']', but got '<stream end>' (line 1, column 13)",
        ),
        (
            ('/math/add', 'example_interfaces/AddTwoInts', '[1, 2]'),
            'The passed value needs to be a dictionary in YAML format',
        ),
        (
            ('/math/add', 'example_interfaces/AddTwoInts', '-r', '0'),
            'rate must be greater than zero',
        ),
    ]
    for args, message in cases:
        result = run_process('service', 'call', *args)
        assert (result.code, result.out, result.err) == (1, '', message + '\n'), args


def test_call_timeout_when_nobody_serves(ros_router: str) -> None:
    start = time.monotonic()
    result = run_process('service', 'call', '/nobody', 'std_srvs/srv/Trigger', '--timeout', '0.5')
    assert result.code == 1
    assert result.out == 'waiting for service to become available...\n'
    assert result.err == "Timed out after 0.5 s waiting for service '/nobody'\n"
    assert time.monotonic() - start < 30


def test_ctrl_c_stops_the_wait_even_when_sigint_came_ignored(adder: Any) -> None:
    # a background job of a shell script starts with SIGINT ignored; ros2cli stops on it anyway
    proc = subprocess.Popen(
        [
            sys.executable,
            '-m',
            'ros2lite',
            'service',
            'call',
            '/nobody/serves/this',
            'example_interfaces/srv/AddTwoInts',
            '{a: 1}',
        ],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN),
    )
    assert proc.stdout is not None
    assert proc.stdout.readline() == 'waiting for service to become available...\n'
    proc.send_signal(signal.SIGINT)
    _out, err = proc.communicate(timeout=20)
    assert proc.returncode == 2 and 'Traceback' not in err
