"""Absurd numbers on the command line are usage errors (exit 2) naming the option: NaN,
infinities, negatives and values no clock or buffer can hold."""

from __future__ import annotations

from typing import Any

import pytest

# topic pub has an option `-1` (--once), so there, as in argparse, `-1` is never a value:
# a negative number is given as `-r=-1`
CASES = [
    ('topic', 'pub', '/x', 'std_msgs/msg/String', '{}', '--max-wait-time-secs', 'nan'),
    ('topic', 'pub', '/x', 'std_msgs/msg/String', '{}', '-r', 'inf'),
    ('topic', 'pub', '/x', 'std_msgs/msg/String', '{}', '-r=-1'),
    ('topic', 'pub', '/x', 'std_msgs/msg/String', '{}', '-t=-1'),
    ('topic', 'pub', '/x', 'std_msgs/msg/String', '{}', '-t', '99999999999999999999999'),
    ('topic', 'pub', '/x', 'std_msgs/msg/String', '{}', '--keep-alive', '1e300'),
    ('topic', 'pub', '/x', 'std_msgs/msg/String', '{}', '-p=-3'),
    ('topic', 'echo', '/x', '--timeout', 'nan'),
    ('topic', 'echo', '/x', '-l', '-1'),
    ('topic', 'echo', '/x', '--qos-depth', '99999999999999999999'),
    ('topic', 'echo', '/x', '--qos-liveliness-lease-duration-seconds=-inf'),  # -i is an option
    ('topic', 'hz', '/x', '-w', '0'),
    ('topic', 'hz', '/x', '-w', '1e3'),
    ('topic', 'list', '--spin-time', 'nan'),
    ('service', 'call', '/s', 'std_srvs/srv/Empty', '-r', 'nan'),
    ('service', 'call', '/s', 'std_srvs/srv/Empty', '--timeout', 'inf'),
    ('action', 'send_goal', '/a', 'example_interfaces/action/Fibonacci', '{}', '--timeout', '-1'),
    ('param', 'get', '/n', 'p', '--timeout', '-5'),
    ('param', 'get', '/n', 'p', '--service-timeout', 'nan'),
    ('bag', 'record', '-a', '--max-bag-duration', 'nan'),
    ('bag', 'record', '-a', '--max-bag-size', '-1'),
    ('bag', 'record', '-a', '--max-cache-size', '1e9'),
    ('bag', 'record', '-a', '--flush-interval', '0'),
    ('bag', 'record', '-a', '-p', '99999999999999999'),
    ('bag', 'play', 'x', '-r', '0'),
    ('bag', 'play', 'x', '-r', 'nan'),
    ('bag', 'play', 'x', '--clock', 'inf'),
    ('bag', 'play', 'x', '-d', '-1'),
    ('bag', 'play', 'x', '--start-offset', 'nan'),
    ('bag', 'play', 'x', '--read-ahead-queue-size', '0'),
]


@pytest.mark.parametrize('args', CASES, ids=[' '.join(c[:2] + c[-2:]) for c in CASES])
def test_absurd_numbers_are_usage_errors(run: Any, args: tuple[str, ...]) -> None:
    result = run(*args)
    assert result.code == 2, result
    assert 'Invalid value for' in result.err and 'Traceback' not in result.err
