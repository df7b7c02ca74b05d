"""`ros2lite run`: finding the executable, passing arguments through untouched, exit statuses
and ros2run's messages, and Ctrl-C/SIGTERM reaching the child."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from tests.cli.conftest import Result, run_process
from tests.pkg.test_executables import make_ament_prefix
from tests.pkg.workspaces import MINIMAL_PUBLISHER
from tests.spinning import spin_until, wait_until


@pytest.fixture
def scripts(tmp_path: Path) -> dict[str, str]:
    """An ament prefix with small shell executables; returns the env pointing at it."""
    prefix = make_ament_prefix(
        tmp_path,
        'tools',
        {
            'fail3': '#!/bin/sh\nexit 3\n',
            'segv': '#!/bin/sh\nkill -SEGV $$\n',
            'echo_args': '#!/bin/sh\nprintf "%s|" "$@"\necho "FOO=$FOO"\n',
            'a/dup': '#!/bin/sh\n',
            'b/dup': '#!/bin/sh\n',
            'wait_term': '#!/bin/sh\necho ready\nexec sleep 30\n',
            # code written for rclpy, as an ament package installs it
            'rclpy_node': f'#!{sys.executable}\n'
            'import rclpy\nfrom std_msgs.msg import String\n'
            'print(rclpy.__name__, String(data="in a ROS shell").data)\n',
        },
    )
    return {'AMENT_PREFIX_PATH': str(prefix)}


def test_unknown_package(run: Callable[..., Result]) -> None:
    result = run('run', 'no_such_package', 'talker')
    assert (result.code, result.out, result.err) == (1, '', "Package 'no_such_package' not found\n")


def test_unknown_executable(run: Callable[..., Result]) -> None:
    result = run('run', 'demo_nodes_py', 'nope')
    assert (result.code, result.err) == (1, 'No executable found\n')


def test_missing_arguments_is_a_usage_error(run: Callable[..., Result]) -> None:
    assert run('run', 'demo_nodes_py').code == 2


def test_multiple_executables(scripts: dict[str, str]) -> None:
    result = run_process('run', 'tools', 'dup', env=scripts)
    prefix = Path(scripts['AMENT_PREFIX_PATH'])
    assert result.code == 1
    assert result.err == (
        f'Multiple executables found:\n- {prefix}/lib/tools/a/dup\n- {prefix}/lib/tools/b/dup\n'
    )


def test_child_failure_status(scripts: dict[str, str]) -> None:
    result = run_process('run', 'tools', 'fail3', env=scripts)
    assert result.code == 3
    assert result.err == '[ros2run]: Process exited with failure 3\n'


def test_child_killed_by_signal(scripts: dict[str, str]) -> None:
    result = run_process('run', 'tools', 'segv', env=scripts)
    assert result.code == 128 + signal.SIGSEGV
    assert result.err == '[ros2run]: Segmentation fault\n'


def test_arguments_and_prefix_pass_through(scripts: dict[str, str]) -> None:
    result = run_process(
        'run',
        '--prefix',
        'env FOO=from_prefix',
        'tools',
        'echo_args',
        '--ros-args',
        '-r',
        'chatter:=/x',
        '--help',
        '-h',
        '--prefix',
        'p',
        env=scripts,
    )
    assert result.code == 0, result.err
    assert result.out == '--ros-args|-r|chatter:=/x|--help|-h|--prefix|p|FOO=from_prefix\n'
    assert result.err == ''


def test_children_get_the_ros_shell_environment(scripts: dict[str, str]) -> None:
    """`run` needs no `ros2lite env` first: its child imports rclpy and interface packages
    even from a shell without PYTHONPATH."""
    os_env = {k: v for k, v in os.environ.items() if k != 'PYTHONPATH'}
    proc = subprocess.run(
        [sys.executable, '-m', 'ros2lite', 'run', 'tools', 'rclpy_node'],
        capture_output=True,
        text=True,
        timeout=60,
        env={**os_env, **scripts},
    )
    assert (proc.returncode, proc.stdout) == (0, 'rclpy in a ROS shell\n'), proc.stderr


def start_run(processes: Any, *args: str, **kw: Any) -> subprocess.Popen[str]:
    # a new session: no controlling terminal, like a script or a service manager
    return processes.start(
        [sys.executable, '-m', 'ros2lite', 'run', *args],
        stdin=subprocess.DEVNULL,
        start_new_session=True,
        **kw,
    )


def test_run_talker_then_ctrl_c(ros_context: Any, processes: Any) -> None:
    node = Node('run_probe', context=ros_context)
    got: list[str] = []
    node.create_subscription(
        'std_msgs/msg/String', '/run_chatter', lambda m: got.append(m.data), 10
    )
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    proc = start_run(
        processes,
        'demo_nodes_py',
        'talker',
        '--ros-args',
        '-r',
        'chatter:=/run_chatter',
        '-r',
        '__node:=run_talker',
    )
    spin_until(ex, lambda: got, timeout=10)
    assert got[0] == 'Hello World: 0'
    # peers send data directly while their tokens go through the router: the graph may show
    # the talker a moment after its first message (discovery is eventually consistent)
    spin_until(ex, lambda: ('run_talker', '/') in node.get_node_names_and_namespaces())
    _out, err = processes.stop(proc)  # SIGINT to `ros2lite run` only
    assert proc.returncode == 0, err
    assert '[talker]' not in err and '[run_talker]: Publishing: "Hello World: 0"' in err
    assert 'Traceback' not in err and '[ros2run]' not in err


def test_sigterm_is_forwarded_and_the_demo_leaves_cleanly(ros_context: Any, processes: Any) -> None:
    probe = Node('sigterm_probe', context=ros_context, enable_rosout=False)
    proc = start_run(
        processes, 'demo_nodes_py', 'listener', '--ros-args', '-r', '__node:=sigterm_listener'
    )
    wait_until(
        lambda: ('sigterm_listener', '/') in probe.get_node_names_and_namespaces(), timeout=10
    )
    proc.send_signal(signal.SIGTERM)
    _out, err = proc.communicate(timeout=10)
    # as an rclpy demo: SIGTERM ends spinning (ExternalShutdownException), status 0
    assert proc.returncode == 0, err
    assert 'Traceback' not in err and '[ros2run]' not in err
    wait_until(
        lambda: ('sigterm_listener', '/') not in probe.get_node_names_and_namespaces(), timeout=5
    )


def test_sigterm_death_of_the_child(scripts: dict[str, str], processes: Any) -> None:
    proc = start_run(processes, 'tools', 'wait_term', env={**os.environ, **scripts})
    assert proc.stdout.readline() == 'ready\n'
    proc.send_signal(signal.SIGTERM)
    _out, err = proc.communicate(timeout=10)
    assert proc.returncode == 128 + signal.SIGTERM
    assert err.strip().splitlines()[-1] == '[ros2run]: Terminated'


def test_sigkill_of_run_takes_the_child_along(scripts: dict[str, str], processes: Any) -> None:
    """R-L16: the node ran on with ppid 1 after its `run` was SIGKILLed."""
    proc = start_run(processes, 'tools', 'wait_term', env={**os.environ, **scripts})
    assert proc.stdout.readline() == 'ready\n'
    children = Path(f'/proc/{proc.pid}/task/{proc.pid}/children')
    [child] = [int(c) for c in children.read_text().split()]
    proc.kill()
    proc.wait(timeout=10)
    wait_until(lambda: not _alive(child), timeout=10)


def _alive(pid: int) -> bool:
    try:
        state = Path(f'/proc/{pid}/stat').read_text().rsplit(')', 1)[1].split()[0]
    except OSError:
        return False
    return state != 'Z'


def test_ctrl_c_in_a_terminal_reaches_the_child_once(tmp_path: Path) -> None:
    """Typed Ctrl-C goes to the terminal's whole foreground group, child included, so `run`
    must not forward another one; elsewhere (see above) it must forward."""
    import fcntl
    import pty
    import termios

    prefix = make_ament_prefix(
        tmp_path,
        'tools',
        {
            'count_int': (
                '#!/bin/sh\nn=0\ntrap \'n=$((n+1))\' INT\necho ready\n'
                'i=0; while [ $i -lt 15 ]; do sleep 0.1; i=$((i+1)); done\necho "interrupts=$n"\n'
            )
        },
    )
    master, slave = pty.openpty()

    def take_terminal() -> None:
        fcntl.ioctl(0, termios.TIOCSCTTY, 0)

    try:
        proc = subprocess.Popen(
            [sys.executable, '-m', 'ros2lite', 'run', 'tools', 'count_int'],
            stdin=slave,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            start_new_session=True,
            preexec_fn=take_terminal,
            env={**os.environ, 'AMENT_PREFIX_PATH': str(prefix)},
        )
        assert proc.stdout is not None
        assert proc.stdout.readline() == 'ready\n'
        os.killpg(proc.pid, signal.SIGINT)  # what the terminal does on Ctrl-C
        out, err = proc.communicate(timeout=10)
    finally:
        os.close(master)
        os.close(slave)
    assert out == 'interrupts=1\n', err
    assert proc.returncode == 0


def test_a_new_package_runs_without_a_build(
    run: Callable[..., Result], ros_context: Any, processes: Any, tmp_path: Path
) -> None:
    ws = tmp_path / 'ws'
    created = run(
        'pkg',
        'create',
        '--build-type',
        'ament_python',
        'py_pubsub',
        '--destination-directory',
        str(ws / 'src'),
        '--dependencies',
        'rclpy',
        'std_msgs',
    )
    assert created.code == 0, created.err
    pkg = ws / 'src' / 'py_pubsub'
    (pkg / 'py_pubsub' / 'publisher_member_function.py').write_text(MINIMAL_PUBLISHER)
    setup = pkg / 'setup.py'
    setup.write_text(
        setup.read_text().replace(
            "'console_scripts': [\n",
            "'console_scripts': ['talker = py_pubsub.publisher_member_function:main',\n",
        )
    )
    node = Node('ws_probe', context=ros_context, enable_rosout=False)
    got: list[str] = []
    node.create_subscription('std_msgs/msg/String', '/ws_topic', lambda m: got.append(m.data), 10)
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    proc = processes.start(
        [
            sys.executable,
            '-m',
            'ros2lite',
            'run',
            'py_pubsub',
            'talker',
            '--ros-args',
            '-r',
            'topic:=/ws_topic',
        ],
        stdin=subprocess.DEVNULL,
        start_new_session=True,
        cwd=pkg / 'py_pubsub',  # anywhere inside the workspace
    )
    spin_until(ex, lambda: len(got) >= 3, timeout=20)
    assert got[0].startswith('Hello World: ')
    _out, err = processes.stop(proc)
    assert proc.returncode == 0, err
    assert 'Traceback' not in err


def test_cpp_demo_runs_its_python_twin(ros_context: Any, processes: Any) -> None:
    probe = Node('twin_probe', context=ros_context, enable_rosout=False)
    proc = start_run(
        processes, 'demo_nodes_cpp', 'listener', '--ros-args', '-r', '__node:=twin_listener'
    )
    wait_until(lambda: ('twin_listener', '/') in probe.get_node_names_and_namespaces(), 15)
    _out, err = processes.stop(proc)
    assert err.splitlines()[0] == (
        '[ros2run]: demo_nodes_cpp (C++) is not installed; running demo_nodes_py listener, '
        'its Python equivalent'
    )
    assert proc.returncode == 0


def test_python_prefix_runs_the_target_under_pdb(tmp_path: Path) -> None:
    from tests.pkg.workspaces import write_package

    ws = tmp_path / 'ws'
    write_package(
        ws / 'src' / 'dbg',
        'dbg',
        scripts={'show': 'dbg.show:main'},
        modules={
            'dbg/__init__.py': '',
            'dbg/show.py': (
                'import sys\ndef main():\n    print("argv", sys.argv[1:])\n    return 0\n'
            ),
        },
    )
    result = run_process(
        'run',
        '--prefix',
        f'{sys.executable} -m pdb',
        'dbg',
        'show',
        'a',
        'b',
        stdin='continue\nquit\n',
        env={'ROS2LITE_WORKSPACE': str(ws)},
    )
    assert "argv ['a', 'b']" in result.out
    assert '(Pdb)' in result.out


def test_unknown_names_get_close_matches(run: Callable[..., Result]) -> None:
    assert run('run', 'demo_nodes_py', 'listner').err == (
        'No executable found; did you mean: listener, listener_qos?\n'
    )
    assert run('run', 'turtlesin', 'turtlesim_node').err == (
        "Package 'turtlesin' not found; did you mean: turtlesim, turtlesim_msgs?\n"
    )


BIRTHDAY = '''
import ros2lite
from ros2lite.executors import ExternalShutdownException
from ros2lite.msgs.tutorial_interfaces.msg import Age
from ros2lite.node import Node


def main():
    ros2lite.init()
    node = Node('birthday')
    pub = node.create_publisher(Age, 'age', 10)
    node.create_timer(0.1, lambda: pub.publish(Age(years=3, months=2)))
    try:
        ros2lite.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
'''


def test_a_custom_message_package_used_by_another(
    run: Callable[..., Result], processes: Any, tmp_path: Path
) -> None:
    """An ament_cmake package holding Age.msg, used by an ament_python package's node: both
    straight from the workspace, the type known to the node and to a tool alike."""
    src = tmp_path / 'ws' / 'src'
    assert (
        run('pkg', 'create', 'tutorial_interfaces', '--destination-directory', str(src)).code == 0
    )
    (src / 'tutorial_interfaces' / 'msg').mkdir()
    (src / 'tutorial_interfaces' / 'msg' / 'Age.msg').write_text('uint8 years\nuint8 months\n')
    assert (
        run(
            'pkg',
            'create',
            '--build-type',
            'ament_python',
            'ages',
            '--destination-directory',
            str(src),
            '--dependencies',
            'tutorial_interfaces',
        ).code
        == 0
    )
    (src / 'ages' / 'ages' / 'birthday.py').write_text(BIRTHDAY)
    setup = src / 'ages' / 'setup.py'
    setup.write_text(
        setup.read_text().replace(
            "'console_scripts': [\n", "'console_scripts': ['birthday = ages.birthday:main',\n"
        )
    )
    shown = run_process(
        'interface',
        'show',
        'tutorial_interfaces/msg/Age',
        env={'ROS2LITE_WORKSPACE': str(tmp_path / 'ws')},
    )
    assert shown.out == 'uint8 years\nuint8 months\n'

    # the node publishes from its source package; `topic echo`, run elsewhere, knows the
    # type from the same workspace (a process of its own: this one's registry stays as is)
    proc = start_run(processes, 'ages', 'birthday', cwd=src / 'ages')
    echo = processes.start(
        [
            sys.executable,
            '-m',
            'ros2lite',
            'topic',
            'echo',
            '--once',
            '/age',
            'tutorial_interfaces/msg/Age',
        ],
        stdin=subprocess.DEVNULL,
        env={**os.environ, 'ROS2LITE_WORKSPACE': str(tmp_path / 'ws')},
    )
    out, err = echo.communicate(timeout=60)
    assert (echo.returncode, out) == (0, 'years: 3\nmonths: 2\n---\n'), err
    processes.stop(proc)
