"""What the `component` verbs share: the load options and the load itself."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

import click

from ..errors import CliError

if TYPE_CHECKING:
    from ros2lite.components.remote import LoadedNode
    from ros2lite.tools.connection import Connection

F = TypeVar('F', bound=Callable[..., Any])

# rcl_interfaces/msg/Log levels by the names --log-level takes
LOG_LEVELS = {'DEBUG': 10, 'INFO': 20, 'WARN': 30, 'WARNING': 30, 'ERROR': 40, 'FATAL': 50}


def component_options(fn: F) -> F:
    """package_name, plugin_name and the node options of `load` and `standalone`."""
    options = [
        click.argument('package_name'),
        click.argument('plugin_name'),
        click.option('-n', '--node-name', help='Component node name'),
        click.option('--node-namespace', help='Component node namespace'),
        click.option(
            '--log-level', help='Component node log level (DEBUG, INFO, WARN, ERROR, FATAL)'
        ),
        click.option(
            '-r',
            '--remap-rule',
            'remap_rules',
            multiple=True,
            help="Component node remapping rules, in the 'from:=to' form",
        ),
        click.option(
            '-p',
            '--parameter',
            'parameters',
            multiple=True,
            help="Component node parameters, in the 'name:=value' form",
        ),
        click.option(
            '-e',
            '--extra-argument',
            'extra_arguments',
            multiple=True,
            help="Extra arguments for the container, in the 'name:=value' form",
        ),
    ]
    for option in reversed(options):
        fn = option(fn)
    return fn


def log_level_number(level: str | None) -> int:
    """--log-level as a Log level number (0: not given)."""
    if level is None:
        return 0
    if level.isdigit():
        return int(level)
    number = LOG_LEVELS.get(level.upper())
    if number is None:
        raise CliError(f"Invalid log level '{level}' (use DEBUG, INFO, WARN, ERROR or FATAL)")
    return number


def load(conn: Connection, container: str, options: dict[str, Any]) -> LoadedNode:
    """Load the component `options` describe into `container`; CliError when refused."""
    from ros2lite.components.remote import ContainerError, RemoteContainer, parse_assignments

    try:
        return RemoteContainer(conn.node(), container).load(
            options['package_name'],
            options['plugin_name'],
            node_name=options['node_name'],
            node_namespace=options['node_namespace'],
            log_level=log_level_number(options['log_level']),
            remap_rules=list(options['remap_rules']),
            parameters=parse_assignments(options['parameters']),
            extra_arguments=parse_assignments(options['extra_arguments']),
        )
    except ContainerError as e:
        raise CliError(str(e)) from None


def unable_to_find(container: str) -> CliError:
    """ros2cli's error for a name that is no container node."""
    return CliError(f"Unable to find container node '{container}'")
