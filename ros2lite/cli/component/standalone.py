"""`component standalone`: start a container of its own and load one component into it.

The container runs as a child (Ctrl-C reaches it, as with `run`); the verb ends when it
does, with its exit status. A Python component goes into ros2lite's container, a C++ one
into rclcpp_components' (which needs a ROS install on AMENT_PREFIX_PATH).
"""

from __future__ import annotations

import signal
import subprocess
import uuid
from typing import Any

import click

from ..common import connect
from ..errors import CliError
from ..options import strategy_options
from ..parsing import command
from .common import component_options, load

START_TIMEOUT = 30.0  # a container that has not come up by then is given up on


def _container_command(package: str, plugin: str, name: str) -> list[str]:
    from ros2lite.components.registry import ComponentLoadError, find_component
    from ros2lite.pkg.errors import PackageNotFoundError
    from ros2lite.pkg.executables import find_executable

    owner = 'rclpy_components'
    try:
        if not find_component(package, plugin).is_python:
            owner = 'rclcpp_components'
    except ComponentLoadError:
        pass  # the container will say so, as rclcpp's does
    try:
        exe = find_executable(owner, 'component_container')
    except PackageNotFoundError:
        exe = None
    if exe is None:
        raise CliError(f"No component container found in package '{owner}'")
    return exe.command(['--ros-args', '-r', f'__node:={name}'])


@command('standalone')
@strategy_options()
@component_options
@click.option(
    '-c',
    '--container-node-name',
    help='Name of the standalone container node to be run (default: standalone_container_<random>)',
)
def cli(
    container_node_name: str | None, no_daemon: bool, use_sim_time: bool, **options: Any
) -> None:
    """Run a component into its own standalone container node."""
    from ros2lite.components.remote import wait_for_container
    from ros2lite.util.process import exit_code, run_child

    name = container_node_name or 'standalone_container_' + uuid.uuid4().hex[:12]
    full = name if name.startswith('/') else '/' + name

    def load_into(child: subprocess.Popen[bytes]) -> None:
        with connect(no_daemon=no_daemon, use_sim_time=use_sim_time) as conn:
            if not wait_for_container(
                conn.entities, full, START_TIMEOUT, lambda: child.poll() is None
            ):
                if child.poll() is None:
                    click.echo(f"Container '{full}' did not come up, terminating container.")
                    child.send_signal(signal.SIGINT)
                return
            try:
                load(conn, full, options)
            except CliError as e:
                click.echo(f'{e}, terminating container.')
                child.send_signal(signal.SIGINT)

    code = run_child(
        _container_command(options['package_name'], options['plugin_name'], name), load_into
    )
    raise click.exceptions.Exit(exit_code(code))
