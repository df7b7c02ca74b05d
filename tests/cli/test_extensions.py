"""`extensions` and `extension_points`: our command and verb tables in ros2cli's format."""

from __future__ import annotations

from collections.abc import Callable

from ros2lite.cli.main import COMMANDS
from tests.cli.conftest import Result

Run = Callable[..., Result]


def test_extension_points(run: Run) -> None:
    lines = run('extension_points').out.splitlines()
    assert "ros2cli.command: The extension point for 'command' extensions" in lines
    assert "ros2lifecycle.verb: The extension point for 'lifecycle' verb extensions" in lines
    assert "ros2cli.daemon.verb: The extension point for 'daemon' verb extensions" in lines
    assert lines == sorted(lines)
    assert not any(line.startswith('ros2run.verb') for line in lines)  # run has no verbs
    verbose = run('extension_points', '-v').out
    assert 'ros2topic.verb: ' in verbose and '    module_name: ros2lite.cli.topic\n' in verbose


def test_extensions(run: Run) -> None:
    out = run('extensions').out
    groups = [line for line in out.splitlines() if not line.startswith(' ')]
    assert groups == sorted(groups) and 'ros2cli.command' in groups
    commands = out.split('ros2cli.command\n')[1].split('\n', len(COMMANDS))[: len(COMMANDS)]
    assert commands == [f'  {name}: {COMMANDS[name][1]}' for name in sorted(COMMANDS)]
    assert (
        '\nros2component.verb\n  list: Output a list of running containers and components\n' in out
    )
    assert '  echo: Echo a service\n' in out.split('ros2service.verb\n')[1]
    verbose = run('extensions', '-v').out
    assert (
        '  set: Trigger lifecycle state transition\n    module_name: ros2lite.cli.lifecycle.set\n'
        in verbose
    )
