"""The options `multicast send` and `receive` share."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

import click

F = TypeVar('F', bound=Callable[..., Any])

DEFAULT_GROUP = '225.0.0.1'  # ros2lite.tools.multicast's defaults, kept here so --help stays light
DEFAULT_PORT = 49150


def address_options(fn: F) -> F:
    """--group, --port and --interface."""
    fn = click.option(
        '--interface',
        metavar='ADDR',
        help='IPv4 address of the local interface to use (default: any for receive, the '
        'routed one for send); 127.0.0.1 keeps the test on this machine',
    )(fn)
    fn = click.option(
        '--port',
        type=click.IntRange(1, 65535),
        default=DEFAULT_PORT,
        show_default=True,
        help='The multicast port',
    )(fn)
    fn = click.option(
        '--group', default=DEFAULT_GROUP, show_default=True, help='The multicast group address'
    )(fn)
    return fn
