"""What a Node becomes: its command and ROS arguments (names, namespaces, parameters,
remaps) — and the scoped ROS settings that shape it."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

import pytest
import yaml

from ros2lite.launch.context import LaunchContext
from ros2lite.launch.errors import LaunchError
from ros2lite.launch.flow import GroupAction
from ros2lite.launch.ros import (
    Node,
    ParameterFile,
    ParameterValue,
    PushRosNamespace,
    SetParameter,
    SetRemap,
)
from ros2lite.launch.substitutions import LaunchConfiguration


class _Service:
    def __init__(self) -> None:
        self.temp: list[str] = []
        self.logged: list[tuple[str, str, str]] = []

    def add_temp_file(self, path: str) -> None:
        self.temp.append(path)

    def log(self, level: str, name: str, msg: str) -> None:
        self.logged.append((level, name, msg))


@pytest.fixture
def context() -> Any:
    ctx = LaunchContext()
    ctx.service = _Service()
    ctx.launch_configurations['rate'] = '5'
    yield ctx
    for path in ctx.service.temp:
        os.unlink(path)


def _visit(ctx: LaunchContext, *entities: Any) -> None:
    stack = list(reversed(entities))
    while stack:
        more = stack.pop().visit(ctx)
        stack.extend(reversed(more or []))


def _param_file(path: str) -> dict[str, Any]:
    return yaml.safe_load(Path(path).read_text())['/**']['ros__parameters']


def test_node_command(context: Any) -> None:
    node = Node(
        package='demo_nodes_py',
        executable='talker',
        name='speaker',
        namespace='robot1',
        parameters=[
            {'rate': LaunchConfiguration('rate'), 'label': 'text', 'nested': {'a': 1, 'b': '2'}},
            {'typed': ParameterValue('7', value_type=str), 'flag': 'true', 'mixed': '[1, a]'},
        ],
        remappings=[('chatter', 'words')],
        arguments=['--extra'],
        ros_arguments=['--log-level', 'debug'],
    )
    _visit(context, SetParameter('use_sim_time', True), SetRemap('/a', '/b'))
    cmd, display, pythonpath = node.command(context)
    assert cmd[1:5] == [
        '-m',
        'ros2lite.pkg.runner',
        'ros2lite.bundled.demo_nodes_py.talker:main',
        'talker',
    ]
    assert display[0].endswith('ros2lite/bundled/demo_nodes_py/talker.py')
    ros = cmd[cmd.index('--ros-args') + 1 :]
    assert cmd[5] == '--extra'
    assert ros[:4] == ['-r', '__node:=speaker', '-r', '__ns:=/robot1']
    assert ros[4] == '--params-file'
    assert _param_file(ros[5]) == {
        'use_sim_time': True,
        'rate': 5,
        'label': 'text',
        'nested.a': 1,
        'nested.b': 2,
        'typed': '7',
        'flag': True,
        'mixed': '[1, a]',
    }
    assert ros[6:] == ['-r', '/a:=/b', '-r', 'chatter:=words', '--log-level', 'debug']
    assert node.label(context, display) == 'talker'
    assert pythonpath == []


def test_namespaces_nest_inside_groups(context: Any) -> None:
    inner = Node(package='demo_nodes_py', executable='listener', namespace='arm')
    absolute = Node(package='demo_nodes_py', executable='listener', namespace='/fixed')
    seen: dict[str, list[str]] = {}

    class Probe:
        def __init__(self, key: str, node: Node) -> None:
            self.key, self.node = key, node

        def visit(self, ctx: LaunchContext) -> None:
            seen[self.key] = self.node.ros_args(ctx)

    _visit(
        context,
        GroupAction(
            [
                PushRosNamespace('robot'),
                PushRosNamespace('sub'),
                Probe('in', inner),
                Probe('abs', absolute),
            ]
        ),
        Probe('out', inner),
    )
    assert seen['in'] == ['-r', '__ns:=/robot/sub/arm']
    assert seen['abs'] == ['-r', '__ns:=/fixed']
    assert seen['out'] == ['-r', '__ns:=/arm']  # the group's namespace did not leak out
    with pytest.raises(LaunchError, match="invalid namespace '/bad name'"):
        _visit(context, PushRosNamespace('/bad name'))


def test_parameter_files(context: Any, tmp_path: Path) -> None:
    params = tmp_path / 'p.yaml'
    params.write_text('/**:\n  ros__parameters:\n    rate: $(var rate)\n')
    node = Node(
        package='demo_nodes_py',
        executable='talker',
        parameters=[str(params), ParameterFile(params, allow_substs=True)],
    )
    ros = node.ros_args(context)
    assert ros[:2] == ['--params-file', str(params)]
    assert _param_file(ros[3]) == {'rate': 5}


def test_unknown_executable_is_an_error_naming_close_matches(context: Any) -> None:
    from ros2lite.pkg.executables import ExecutableNotFoundError

    with pytest.raises(ExecutableNotFoundError, match='did you mean: talker'):
        Node(package='demo_nodes_py', executable='talkr').command(context)
