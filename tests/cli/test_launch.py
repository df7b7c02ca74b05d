"""`ros2lite launch` end to end: Python, XML and YAML launch files from a source workspace
start real nodes (namespace, remap, parameters from a dict and a file, an included file
given an argument); Ctrl-C stops every child; `-s`/`-p` and the errors."""

from __future__ import annotations

import os
import random
import re
import shutil
import signal
import subprocess
import sys
import threading
import time
import uuid
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import pytest

from ros2lite.node import Node
from tests.cli.conftest import Result, run_process
from tests.pkg.workspaces import write_package
from tests.spinning import wait_until

FILES = Path(__file__).resolve().parent / 'launch_files'

# a node that says what it was given (name, namespace, arguments, parameters), then ends
SHOW = """
import sys

import ros2lite
from ros2lite.node import Node


def main(args=None):
    ros2lite.init(args=args)
    node = Node('show', automatically_declare_parameters_from_overrides=True)
    own = sys.argv[1:sys.argv.index('--ros-args')]
    values = {n: node.get_parameter(n).value for n in ('answer', 'label', 'greeting')}
    print(node.get_fully_qualified_name(), own, values, flush=True)
    ros2lite.shutdown()
"""


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    """A workspace whose `lesson_bringup` package holds the lesson's launch files (unbuilt)."""
    ws = tmp_path / 'ws'
    pkg = write_package(
        ws / 'src' / 'lesson_bringup',
        'lesson_bringup',
        scripts={'show': 'lesson_bringup.show:main'},
        modules={'lesson_bringup/__init__.py': '', 'lesson_bringup/show.py': SHOW},
    )
    (pkg / 'launch').mkdir()
    (pkg / 'config').mkdir()
    for f in FILES.iterdir():
        if '.launch.' in f.name:
            shutil.copy(f, pkg / 'launch' / f.name)
    shutil.copy(FILES / 'board.yaml', pkg / 'config' / 'board.yaml')
    return ws


class Launch:
    """A `ros2lite launch` process whose output lines are collected by a thread."""

    def __init__(self, proc: subprocess.Popen[str]) -> None:
        self.proc = proc
        self.lines: list[str] = []
        self._pumping = threading.Thread(target=self._pump, daemon=True)
        self._pumping.start()

    def _pump(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self.lines.append(line.rstrip('\n'))

    def wait_for(self, text: str, timeout: float = 30.0) -> str:
        found = wait_until(
            lambda: next((line for line in self.lines if text in line), None), timeout=timeout
        )
        return str(found)

    def interrupt(self, timeout: float = 30.0) -> int:
        self.proc.send_signal(signal.SIGINT)
        code = self.proc.wait(timeout)
        # its last lines may still be in the pipe: read up to the end before anyone looks
        self._pumping.join(timeout)
        return code


def start_launch(processes: Any, *args: str, cwd: Path | None = None, **env: str) -> Launch:
    proc = processes.start(
        [sys.executable, '-m', 'ros2lite', 'launch', *args],
        stdin=subprocess.DEVNULL,
        stderr=subprocess.STDOUT,
        start_new_session=True,
        cwd=cwd,
        env={**os.environ, **env},
    )
    return Launch(proc)


@pytest.mark.parametrize('flavour', ['py', 'xml', 'yaml'])
def test_the_lesson_in_each_format(
    flavour: str,
    workspace: Path,
    ros_context: Any,
    processes: Any,
    run: Callable[..., Result],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    ns = f'lesson_{flavour}'
    launch = start_launch(
        processes,
        'lesson_bringup',
        f'top.launch.{flavour}',
        f'ns:={ns}',
        'topic:=said',
        cwd=workspace / 'src',
    )
    heard = launch.wait_for('I heard: [Hello World: ')
    assert f'[{ns}.listener]' in heard and heard.startswith('[listener-3] [INFO] [')
    assert launch.lines[0].startswith('[INFO] [launch]: All log files can be found below ')
    probe = Node(f'launch_probe_{flavour}', context=ros_context, enable_rosout=False)
    nodes = {('speaker', f'/{ns}'), ('board', f'/{ns}'), ('listener', f'/{ns}')}
    wait_until(lambda: nodes <= set(probe.get_node_names_and_namespaces()), timeout=15)
    topics = dict(probe.get_topic_names_and_types())
    assert topics.get(f'/{ns}/said') == ['std_msgs/msg/String']
    monkeypatch.chdir(workspace)
    assert run('param', 'get', f'/{ns}/board', 'answer').out == 'Integer value is: 42\n'
    assert run('param', 'get', f'/{ns}/board', 'greeting').out == (
        'String value is: hello from a file\n'
    )
    assert launch.interrupt() == 0
    for label in ('talker-1', 'parameter_blackboard-2', 'listener-3'):
        assert any(f'[INFO] [{label}]: process has finished cleanly' in x for x in launch.lines)
    assert not any('Traceback' in line for line in launch.lines), launch.lines


def _descendants(marker: str) -> list[int]:
    """Processes (of any session or group) carrying the trial's marker in their environment."""
    found = []
    for entry in os.listdir('/proc'):
        if not entry.isdigit():
            continue
        try:
            with open(f'/proc/{entry}/environ', 'rb') as f:
                if marker.encode() in f.read():
                    found.append(int(entry))
        except OSError:
            continue
    return found


@pytest.fixture
def terminal() -> Iterator[int]:
    """A pseudo-terminal for the launch: Ctrl-C typed there goes to its foreground group."""
    import pty

    master, slave = pty.openpty()
    yield slave
    os.close(master)
    os.close(slave)


def test_ctrl_c_leaves_no_child_behind(ros_router: str, terminal: int) -> None:
    """Ctrl-C at random moments, from starting up to talking: every process the launch
    started is gone when it returns, and it returns 0 without escalating."""
    import fcntl
    import termios

    def take_terminal() -> None:
        fcntl.ioctl(0, termios.TIOCSCTTY, 0)

    for delay in (0.05, random.uniform(0.2, 0.8), None, None):
        marker = f'ROS2LITE_TRIAL={uuid.uuid4().hex}'
        name, value = marker.split('=')
        proc = subprocess.Popen(
            [
                sys.executable,
                '-m',
                'ros2lite',
                'launch',
                'demo_nodes_py',
                'talker_listener.launch.py',
            ],
            stdin=terminal,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            start_new_session=True,
            preexec_fn=take_terminal,
            env={**os.environ, name: value},
        )
        launch = Launch(proc)
        try:
            if delay is None:
                launch.wait_for('I heard: [Hello World: ')  # both nodes up and talking
            else:
                time.sleep(delay)  # deliberately early: during start-up
            os.killpg(proc.pid, signal.SIGINT)  # what the terminal does on Ctrl-C
            code = proc.wait(30)
        finally:
            if proc.poll() is None:
                proc.kill()
        wait_until(lambda m=marker: not _descendants(m), timeout=10)
        if any('process started' in line for line in launch.lines):
            # the launch was running: it stopped its children in order, and says so
            assert code == 0, launch.lines
            assert not any('escalating' in line for line in launch.lines), launch.lines
        # else Ctrl-C came while Python was still importing: nothing was started


def test_every_feature_a_course_names(workspace: Path) -> None:
    """features.launch.py: the Python launch API of a ROS course, by its ROS names, run to
    its natural end (every process exits, so the launch does)."""
    result = run_process(
        'launch',
        'lesson_bringup',
        'features.launch.py',
        'mode:=fast',
        env={'ROS2LITE_WORKSPACE': str(workspace), 'LESSON_WHO': 'student'},
    )
    assert result.code == 0, result.out + result.err
    lines = result.out.splitlines()
    assert '[greet-1] hello student' in lines  # TextSubstitution + EnvironmentVariable
    assert '[INFO] [launch.user]: greet is done' in lines  # OnProcessExit
    assert '[echo-2] without extra' in lines  # UnlessCondition
    assert not any('with extra' in line for line in lines if 'without' not in line)
    assert '[INFO] [launch.user]: mode is fast' in lines  # OpaqueFunction + the argument
    # TimerAction, GroupAction + PushRosNamespace, SetParameter, a dict and a file
    # (FindPackageShare + PathJoinSubstitution), arguments, and output to the screen
    assert (
        "[show-3] /feat/shower ['--mode', 'fast'] "
        "{'answer': 42, 'label': 'from a dict', 'greeting': 'hello from a file'}"
    ) in lines
    assert any(line.startswith('[INFO] [show-3]: process has finished cleanly') for line in lines)
    shown = run_process(
        'launch',
        'lesson_bringup',
        'features.launch.py',
        '-s',
        env={'ROS2LITE_WORKSPACE': str(workspace)},
    )
    assert "    'mode':\n        how to run\n        (default: 'slow')\n" in shown.out
    assert "    'extra':\n        one more\n        (default: 'false')\n" in shown.out


def test_show_args_and_print(
    run: Callable[..., Result], workspace: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.chdir(workspace)  # the include's FindPackageShare finds the workspace
    shown = run('launch', 'lesson_bringup', 'top.launch.py', '-s')
    assert shown.code == 0, shown.err
    assert shown.out.startswith(
        "Arguments (pass arguments as '<name>:=<value>'):\n\n    'ns':\n        namespace\n"
        "        (default: 'lesson')\n\n    'topic':\n        topic to use\n"
    )
    assert "'heard_topic':" in shown.out  # from the included file
    printed = run('launch', 'demo_nodes_py', 'talker_listener.launch.xml', '--print')
    assert printed.out.splitlines()[1:] == [
        "├── Node(package='demo_nodes_py', executable='talker')",
        "└── Node(package='demo_nodes_py', executable='listener')",
    ]


def test_prefix_filter_and_all_output(tmp_path: Path) -> None:
    """`--launch-prefix` goes before every executable (or those `--launch-prefix-filter`
    matches); `-a` shows the output of processes whose output goes to the log only."""
    path = tmp_path / 'two.launch.py'
    path.write_text(
        'from launch import LaunchDescription\n'
        'from launch.actions import ExecuteProcess\n\n'
        'def generate_launch_description():\n'
        '    return LaunchDescription([\n'
        "        ExecuteProcess(cmd=['echo', 'quiet'], output='log'),\n"
        "        ExecuteProcess(cmd=['printf', 'loud'], output='screen'),\n"
        '    ])\n'
    )

    def screen(*options: str) -> list[str]:
        result = run_process('launch', *options, str(path))
        assert result.code == 0, result.out + result.err
        # two processes at once: their lines may come in either order
        return sorted(line for line in result.out.splitlines() if not line.startswith('[INFO]'))

    assert screen() == ['[printf-2] loud']
    assert screen('-a') == ['[echo-1] quiet', '[printf-2] loud']
    assert screen('-a', '--launch-prefix', 'echo with') == [
        '[echo-1] with echo quiet',
        '[printf-2] with printf loud',
    ]
    filtered = screen('-a', '--launch-prefix', 'echo with', '--launch-prefix-filter', 'pri.tf')
    assert filtered == ['[echo-1] quiet', '[printf-2] with printf loud']


def test_errors(run: Callable[..., Result], workspace: Path) -> None:
    missing = run('launch', 'demo_nodes_py', 'nope.launch.py')
    assert missing.code == 1
    assert missing.err.startswith(
        "file 'nope.launch.py' was not found in the share directory of package 'demo_nodes_py'"
    )
    assert run('launch', 'demo_nodes_py', 'talker_listener.launch.py', 'oops').err == (
        "malformed launch argument 'oops', expected format '<name>:=<value>'\n"
    )
    assert run('launch', 'no_such_pkg', 'x.launch.py').err == ("Package 'no_such_pkg' not found\n")
    assert 'is not a launch file' in run('launch', 'no_such_file.launch.py').err


def test_a_required_argument_missing(workspace: Path) -> None:
    path = workspace / 'src' / 'lesson_bringup' / 'launch' / 'listen.launch.py'
    result = run_process('launch', str(path))
    assert result.code == 1
    assert result.out.splitlines()[-1] == (
        '[ERROR] [launch]: Caught exception in launch (see debug for traceback): Included '
        "launch description missing required argument 'heard_topic' (description: 'no "
        "description given'), given: []"
    )


def _screen_of_a_launch_in_a_terminal(env: dict[str, str]) -> str:
    """What a terminal shows of a two-node launch until the listener hears the talker and
    the talker's own line is there."""
    import pty
    import select

    master, slave = pty.openpty()
    proc = subprocess.Popen(
        [sys.executable, '-m', 'ros2lite', 'launch', 'demo_nodes_py', 'talker_listener.launch.py'],
        stdin=subprocess.DEVNULL,
        stdout=slave,
        stderr=slave,
        start_new_session=True,
        env=env,
    )
    os.close(slave)
    seen = b''
    try:
        deadline = time.monotonic() + 30
        # both nodes' own lines: the listener may hear before the talker's line is flushed
        while not (b'I heard' in seen and b'Publishing' in seen) and time.monotonic() < deadline:
            ready, _, _ = select.select([master], [], [], 0.5)
            if ready:
                seen += os.read(master, 65536)
    finally:
        proc.send_signal(signal.SIGINT)
        proc.wait(30)
        os.close(master)
    return seen.decode(errors='replace')


def test_a_colour_per_process_on_a_terminal(ros_router: str) -> None:
    env = {k: v for k, v in os.environ.items() if k != 'NO_COLOR'}
    screen = _screen_of_a_launch_in_a_terminal(env)
    talker = re.search(r'((?:\x1b\[[0-9;]*m)+)\[talker-1\]', screen)
    listener = re.search(r'((?:\x1b\[[0-9;]*m)+)\[listener-2\]', screen)
    assert talker and listener, screen
    assert talker.group(1) != listener.group(1)  # one colour each
    plain = _screen_of_a_launch_in_a_terminal({**env, 'NO_COLOR': '1'})
    assert '[talker-1]' in plain and '\x1b[' not in plain


def test_sigterm_stops_every_child_too(processes: Any) -> None:
    """launch itself leaves its processes behind on SIGTERM; ros2lite stops them in order."""
    marker = f'ROS2LITE_TRIAL={uuid.uuid4().hex}'
    name, value = marker.split('=')
    launch = start_launch(processes, 'demo_nodes_py', 'talker_listener.launch.py', **{name: value})
    launch.wait_for('I heard: [Hello World: ')
    launch.proc.send_signal(signal.SIGTERM)
    assert launch.proc.wait(30) == 0
    wait_until(lambda: not _descendants(marker), timeout=10)
    assert '[WARNING] [launch]: received SIGTERM, stopping every process' in launch.lines
    assert "[INFO] [talker-1]: sending signal 'SIGINT' to process[talker-1]" in launch.lines
