"""`component list|load|unload|types|standalone` with ros2lite's containers as real
processes (single- and multi-threaded)."""

from __future__ import annotations

import subprocess
import sys
import threading
from collections.abc import Callable
from typing import Any

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from tests.cli.conftest import Result
from tests.spinning import spin_until, wait_until

String = get_interface('std_msgs/msg/String')
Run = Callable[..., Result]


class Lines:
    """Collects what a process writes on one stream, line by line, while it runs."""

    def __init__(self, stream: Any) -> None:
        self.lines: list[str] = []
        self.thread = threading.Thread(target=lambda: self.lines.extend(stream), daemon=True)
        self.thread.start()

    def has(self, text: str) -> bool:
        return any(text in line for line in self.lines)


def container(processes: Any, name: str, executable: str = 'component_container') -> Any:
    return processes.cli(
        'run', 'rclpy_components', executable, '--ros-args', '-r', f'__node:={name}'
    )


def wait_for_container(run: Run, name: str) -> None:
    wait_until(lambda: name in run('component', 'list', '--containers-only').out, timeout=20)


def test_load_list_unload(run: Run, processes: Any, ros_context: Any) -> None:
    proc = container(processes, 'cli_container')
    log = Lines(proc.stderr)
    wait_for_container(run, '/cli_container')
    observer = Node('component_observer', context=ros_context, enable_rosout=False)
    heard: list[str] = []
    observer.create_subscription(String, '/cli/chatter', lambda m: heard.append(m.data), 10)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(observer)
    try:
        ns = ('--node-namespace', '/cli')
        talker = run(
            'component', 'load', '/cli_container', 'composition', 'composition::Talker', *ns
        )
        assert (talker.code, talker.out) == (
            0,
            "Loaded component 1 into '/cli_container' container node as '/cli/talker'\n",
        )
        listener = run(
            'component', 'load', '/cli_container', 'composition', 'composition::Listener', *ns
        )
        assert listener.out.endswith("as '/cli/listener'\n")
        spin_until(executor, lambda: len(heard) >= 2, timeout=15)
        assert heard[:2] == ['Hello World: 1', 'Hello World: 2']
        wait_until(lambda: log.has('[cli.listener]: I heard: [Hello World: 1]'))
        assert (
            run('component', 'list', '/cli_container').out == '1  /cli/talker\n2  /cli/listener\n'
        )
        listed = run('component', 'list').out
        assert '/cli_container\n  1  /cli/talker\n  2  /cli/listener\n' in listed

        quiet = run(
            'component', 'load', '-q', '/cli_container', 'composition', 'composition::Server'
        )
        assert quiet.out == '3\n'
        gone = run('component', 'unload', '/cli_container', '1', '3')
        assert gone.out == (
            "Unloaded component 1 from '/cli_container' container node\n"
            "Unloaded component 3 from '/cli_container' container node\n"
        )
        assert run('component', 'list', '/cli_container').out == '2  /cli/listener\n'
        again = run('component', 'unload', '/cli_container', '1')
        assert (again.code, again.err) == (
            1,
            "Failed to unload component 1 from '/cli_container' container node\n"
            '    No node found with unique_id: 1\n',
        )
        nope = run('component', 'load', '/cli_container', 'composition', 'composition::Nope')
        assert (nope.code, nope.err) == (
            1,
            'Failed to load component: Failed to find class with the requested plugin name.\n',
        )
        missing = run('component', 'load', '/nope', 'composition', 'composition::Talker')
        assert (missing.code, missing.err) == (1, "Unable to find container node '/nope'\n")
        assert run('component', 'list', '/nope').err == "Unable to find container node '/nope'\n"
    finally:
        executor.shutdown()
        observer.destroy_node()
    processes.stop(proc)
    log.thread.join(timeout=5)
    assert proc.returncode == 0 and not log.has('Traceback')


def test_types(run: Run) -> None:
    listed = run('component', 'types').out
    assert (
        'composition\n  composition::Talker\n  composition::Listener\n'
        '  composition::Server\n  composition::Client\n'
    ) in listed
    assert run('component', 'types', 'composition').out.splitlines()[0] == 'composition::Talker'
    assert run('component', 'types', 'demo_nodes_py').out == ''  # a package, no components
    unknown = run('component', 'types', 'no_such_pkg')
    assert (unknown.code, unknown.err) == (1, "Unable to find package 'no_such_pkg'\n")


def test_multi_threaded_container_runs_client_and_server(run: Run, processes: Any) -> None:
    proc = processes.cli(
        'run',
        'rclpy_components',
        'component_container_mt',
        '--ros-args',
        '-r',
        '__node:=mt_container',
        '-p',
        'thread_num:=2',
    )
    log = Lines(proc.stderr)
    wait_for_container(run, '/mt_container')
    ns = ('--node-namespace', '/mt')
    assert (
        run('component', 'load', '/mt_container', 'composition', 'composition::Server', *ns).code
        == 0
    )
    assert (
        run('component', 'load', '/mt_container', 'composition', 'composition::Client', *ns).code
        == 0
    )
    wait_until(lambda: log.has('[mt.Client]: Got result: [5]'), timeout=20)
    assert log.has('[mt.Server]: Incoming request: [a: 2, b: 3]')
    processes.stop(proc)
    assert proc.returncode == 0


def test_standalone(processes: Any, ros_context: Any) -> None:
    observer = Node('standalone_observer', context=ros_context, enable_rosout=False)
    heard: list[str] = []
    observer.create_subscription(String, '/sa/chatter', lambda m: heard.append(m.data), 10)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(observer)
    proc = processes.cli(
        'component', 'standalone', 'composition', 'composition::Talker',
        '-c', 'sa_container', '--node-namespace', '/sa',
        '--no-daemon', '-s', '--spin-time', '1',  # ros2cli's strategy options
    )  # fmt: skip
    try:
        spin_until(executor, lambda: heard, timeout=20)
        wait_until(lambda: observer.count_services('/sa_container/_container/load_node') == 1)
    finally:
        executor.shutdown()
        observer.destroy_node()
    _out, err = processes.stop(proc)
    assert proc.returncode == 0 and 'Traceback' not in err, err

    failing = subprocess.run(
        [
            sys.executable, '-m', 'ros2lite', 'component', 'standalone',
            'composition', 'composition::Nope', '-c', 'sa_failing',
        ],
        capture_output=True, text=True, timeout=60,
    )  # fmt: skip
    assert failing.stdout == (
        'Failed to load component: Failed to find class with the requested plugin name., '
        'terminating container.\n'
    )
    assert failing.returncode == 0  # the container's own status after Ctrl-C
