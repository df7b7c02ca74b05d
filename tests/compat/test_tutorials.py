"""Code written for rclpy, unchanged: the tutorials' nodes run in a shell set up by
`eval "$(ros2lite env)"` and talk to the CLI verbs (and to each other)."""

from __future__ import annotations

import os
import shlex
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from tests.cli.conftest import run_process
from tests.spinning import wait_until

TUTORIALS = Path(__file__).resolve().parent / 'tutorials'


def in_ros_shell(program: str, *args: str, env: dict[str, str] | None = None) -> list[str]:
    """bash: `eval "$(ros2lite env)"`, then the program with the interpreter of these tests
    (in a fresh terminal that is the python of the environment ros2lite is installed in)."""
    line = ' '.join(shlex.quote(a) for a in (sys.executable, str(TUTORIALS / program), *args))
    return ['bash', '-c', f'eval "$({shlex.quote(sys.executable)} -m ros2lite env)" && exec {line}']


def start(processes: Any, tmp_path: Path, program: str, **kw: Any) -> tuple[Any, Path]:
    """Start a tutorial program; its log lines go to a file the test can poll."""
    log = tmp_path / f'{program}.log'
    env = {k: v for k, v in os.environ.items() if k != 'PYTHONPATH'}
    env.update(kw.pop('env', {}))
    proc = processes.start(
        in_ros_shell(program), stdout=log.open('w'), stderr=subprocess.STDOUT, env=env, **kw
    )
    return proc, log


def logged(log: Path, text: str) -> bool:
    return text in log.read_text()


def test_publisher_is_heard_by_topic_echo(processes: Any, tmp_path: Path) -> None:
    _, log = start(processes, tmp_path, 'talker.py')
    wait_until(lambda: logged(log, 'Publishing: "Hello World: '), timeout=30)
    result = run_process('topic', 'echo', '/topic', 'std_msgs/msg/String', '--once')
    assert result.code == 0, result.err
    assert result.out.startswith("data: 'Hello World: ")


def test_subscriber_hears_topic_pub(processes: Any, tmp_path: Path) -> None:
    _, log = start(processes, tmp_path, 'listener.py')
    result = run_process(
        'topic', 'pub', '--once', '-w', '1', '/topic', 'std_msgs/msg/String', 'data: from the cli'
    )
    assert result.code == 0, result.err
    wait_until(lambda: logged(log, '[minimal_subscriber]: I heard: "from the cli"'), timeout=30)


def test_service_answers_service_call_and_the_client(processes: Any, tmp_path: Path) -> None:
    start(processes, tmp_path, 'add_two_ints_server.py')
    result = run_process(
        'service', 'call', '/add_two_ints', 'example_interfaces/srv/AddTwoInts', '{a: 2, b: 40}'
    )
    assert result.code == 0, result.err
    assert 'example_interfaces.srv.AddTwoInts_Response(sum=42)' in result.out
    client = subprocess.run(
        in_ros_shell('add_two_ints_client.py', '3', '4'),
        capture_output=True,
        text=True,
        timeout=60,
        env={k: v for k, v in os.environ.items() if k != 'PYTHONPATH'},
    )
    assert client.stdout == 'Result of add_two_ints: for 3 + 4 = 7\n', client.stderr


def test_action_server_reached_by_send_goal(processes: Any, tmp_path: Path) -> None:
    start(processes, tmp_path, 'fibonacci_action_server.py')
    result = run_process(
        'action',
        'send_goal',
        '/fibonacci',
        'action_tutorials_interfaces/action/Fibonacci',
        '{order: 5}',
        '--feedback',
    )
    assert result.code == 0, result.err
    assert 'Goal finished with status: SUCCEEDED' in result.out
    assert 'partial_sequence:\n- 0\n- 1\n- 1\n- 2\n- 3\n- 5\n' in result.out
    assert 'sequence:\n- 0\n- 1\n- 1\n- 2\n- 3\n- 5\n' in result.out


def test_parameter_node_and_the_param_verbs(processes: Any, tmp_path: Path) -> None:
    _, log = start(processes, tmp_path, 'param_talker.py')
    wait_until(lambda: logged(log, '[minimal_param_node]: Hello world!'), timeout=30)
    got = run_process('param', 'get', '/minimal_param_node', 'my_parameter')
    assert (got.code, got.out) == (0, 'String value is: world\n'), got.err
    changed = run_process('param', 'set', '/minimal_param_node', 'my_parameter', 'earth')
    assert (changed.code, changed.out) == (0, 'Set parameter successful\n'), changed.err
    wait_until(lambda: logged(log, '[minimal_param_node]: Hello earth!'), timeout=30)


@pytest.fixture
def my_interfaces(tmp_path: Path) -> Path:
    """A package of the user's own: `my_interfaces/msg/Age.msg`, found through
    ROS2LITE_INTERFACE_PATH as in a user's workspace."""
    root = tmp_path / 'interfaces'
    (root / 'my_interfaces' / 'msg').mkdir(parents=True)
    (root / 'my_interfaces' / 'msg' / 'Age.msg').write_text('uint8 years\nstring name\n')
    return root


def test_custom_message_package(processes: Any, tmp_path: Path, my_interfaces: Path) -> None:
    path = {'ROS2LITE_INTERFACE_PATH': str(my_interfaces)}
    start(processes, tmp_path, 'age_talker.py', env=path)
    result = run_process('topic', 'echo', '/age', 'my_interfaces/msg/Age', '--once', env=path)
    assert (result.code, result.out) == (0, 'years: 7\nname: ros2lite\n---\n'), result.err
