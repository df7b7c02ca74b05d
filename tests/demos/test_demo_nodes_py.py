"""The bundled talker/listener as real processes: what they publish and log, `--ros-args`
handling, and a quiet exit on Ctrl-C."""

from __future__ import annotations

import re
import sys
import time
from pathlib import Path
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from tests.spinning import spin_until, wait_until

String = get_interface('std_msgs/msg/String')


def log_line(name: str, text: str) -> str:
    """rcutils' default console line at INFO, as a regex (`text` already a regex)."""
    return r'\[INFO\] \[\d+\.\d{9}\] \[' + re.escape(name) + r'\]: ' + text


def demo(processes: Any, exe: str, *args: str) -> Any:
    return processes.start([sys.executable, '-m', f'ros2lite.demos.demo_nodes_py.{exe}', *args])


def wait_for_node(node: Node, name: str, namespace: str = '/', timeout: float = 10) -> None:
    deadline = time.monotonic() + timeout
    while (name, namespace) not in node.get_node_names_and_namespaces():
        assert time.monotonic() < deadline, node.get_node_names_and_namespaces()
        time.sleep(0.05)


def test_talker(ros_context: Any, processes: Any) -> None:
    node = Node('test_listener', context=ros_context)
    got: list[Any] = []
    node.create_subscription(String, 'chatter', got.append, 10)
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    proc = demo(processes, 'talker')
    spin_until(ex, lambda: len(got) >= 2, timeout=10)
    out, err = processes.stop(proc)
    assert proc.returncode == 0
    assert [m.data for m in got[:2]] == ['Hello World: 0', 'Hello World: 1']
    lines = err.splitlines()
    assert re.fullmatch(log_line('talker', 'Publishing: "Hello World: 0"'), lines[0]), err
    assert re.fullmatch(log_line('talker', 'Publishing: "Hello World: 1"'), lines[1]), err
    assert 'Traceback' not in err and out == ''


def test_talker_publishes_with_depth_10(ros_context: Any, processes: Any) -> None:
    node = Node('qos_probe', context=ros_context)
    proc = demo(processes, 'talker')
    deadline = time.monotonic() + 10
    while not (infos := node.get_publishers_info_by_topic('/chatter')):
        assert time.monotonic() < deadline
        time.sleep(0.05)
    assert infos[0].node_name == 'talker'
    assert infos[0].qos_profile is not None and infos[0].qos_profile.depth == 10
    processes.stop(proc)


def test_listener_with_remapping(ros_context: Any, processes: Any) -> None:
    node = Node('test_talker', context=ros_context)
    pub = node.create_publisher(String, '/other', 10)
    proc = demo(
        processes,
        'listener',
        '--ros-args',
        '-r',
        'chatter:=/other',
        '-r',
        '__node:=lis',
        '-r',
        '__ns:=/ns',
    )
    wait_for_node(node, 'lis', '/ns')
    deadline = time.monotonic() + 5
    while pub.get_subscription_count() < 1:
        assert time.monotonic() < deadline
        time.sleep(0.02)
    assert node.get_subscriber_names_and_types_by_node('lis', '/ns') == [
        ('/other', ['std_msgs/msg/String'])
    ]
    for i in range(3):
        pub.publish(String(data=f'Hello World: {i}'))
    time.sleep(0.5)
    _out, err = processes.stop(proc)
    assert proc.returncode == 0, err
    heard = [line for line in err.splitlines() if 'I heard' in line]
    assert len(heard) == 3, err
    for i, line in enumerate(heard):
        assert re.fullmatch(log_line('ns.lis', rf'I heard: \[Hello World: {i}\]'), line), line
    assert 'Traceback' not in err


def test_parameters_reach_the_node(ros_context: Any, processes: Any) -> None:
    """`-p use_sim_time:=true`: the talker's 1 s timer then runs on `/clock`, not wall time."""
    Clock = get_interface('rosgraph_msgs/msg/Clock')
    Time = get_interface('builtin_interfaces/msg/Time')
    node = Node('clock_source', context=ros_context)
    clock_pub = node.create_publisher(Clock, '/clock', 10)
    got: list[str] = []
    node.create_subscription(String, 'chatter', lambda m: got.append(m.data), 10)
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    proc = demo(processes, 'talker', '--ros-args', '-p', 'use_sim_time:=true')
    wait_for_node(node, 'talker')
    start = time.monotonic()
    while time.monotonic() - start < 1.5:
        ex.spin_once(timeout_sec=0.05)
    assert got == []  # 1.5 s of wall time, but sim time has not moved

    def tick() -> bool:
        clock_pub.publish(Clock(clock=Time(sec=100)))
        ex.spin_once(timeout_sec=0.05)
        return bool(got)

    spin_until(ex, tick)
    assert got[0] == 'Hello World: 0'
    processes.stop(proc)


def threads(pid: int) -> int:
    """How many threads the process runs (one until zenoh's runtime starts)."""
    for line in Path(f'/proc/{pid}/status').read_text().splitlines():
        if line.startswith('Threads:'):
            return int(line.split()[1])
    return 0


def test_ctrl_c_while_starting_is_quiet(processes: Any) -> None:
    """Ctrl-C once the demo has begun joining the graph (its Zenoh session is starting;
    its imports are done: a Ctrl-C during imports is Python's, as with rclpy's demos)."""
    proc = demo(processes, 'listener')
    wait_until(lambda: threads(proc.pid) > 1, timeout=20, interval=0.005)
    _out, err = processes.stop(proc)
    assert proc.returncode == 0
    assert 'Traceback' not in err


def test_no_router_in_client_mode_is_one_line(processes: Any) -> None:
    # nodes start the daemon or run without a router (tests/test_router_survival.py); a
    # client-mode session has no such way out
    from tests.conftest import free_port

    proc = processes.start(
        [sys.executable, '-m', 'ros2lite.demos.demo_nodes_py.talker'],
        env={
            **_env(),
            'ROS2LITE_ROUTER': f'tcp/127.0.0.1:{free_port()}',
            'ZENOH_CONFIG_OVERRIDE': 'mode="client"',
        },
    )
    _out, err = proc.communicate(timeout=10)
    assert proc.returncode == 1
    assert err.count('\n') == 1 and 'No Zenoh router answers' in err


def test_parameter_blackboard(ros_context: Any, processes: Any) -> None:
    """Holds every override and anything set later, as ROS's demo does."""
    from ros2lite.parameter import Parameter, parameter_value_to_python
    from ros2lite.parameter_client import AsyncParameterClient

    proc = demo(
        processes, 'parameter_blackboard', '--ros-args', '-p', 'speed:=2.5', '-p', 'names:=[a, b]'
    )
    client = Node('_blackboard_client', context=ros_context, start_parameter_services=False)
    remote = AsyncParameterClient(client, '/parameter_blackboard')
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(client)

    def wait(future: Any) -> Any:
        executor.spin_until_future_complete(future, 10.0)
        return future.result()

    assert remote.wait_for_services(10.0)
    assert sorted(wait(remote.list_parameters()).result.names) == [
        'names',
        'speed',
        'use_sim_time',
    ]
    assert wait(remote.set_parameters([Parameter('brand_new', value=7)])).results[0].successful
    values = wait(remote.get_parameters(['speed', 'names', 'brand_new'])).values
    assert [parameter_value_to_python(v) for v in values] == [2.5, ['a', 'b'], 7]
    _out, err = processes.stop(proc)
    assert proc.returncode == 0
    assert re.fullmatch(
        log_line(
            'parameter_blackboard',
            re.escape(
                "Parameter blackboard node named '/parameter_blackboard' ready, and serving '3' "
                "parameters already!"
            ),
        ),
        err.splitlines()[0],
    ), err


@pytest.mark.parametrize(
    'args, message',
    [
        (['--ros-args', '-r', '__node:=1bad'], 'invalid node name'),
        (['--ros-args', '--bogus'], "Unknown ROS argument '--bogus'"),
        # an override of another type than the declared default: rclpy's exception, one line
        (['--ros-args', '-p', 'use_sim_time:=3'], "expecting type 'BOOL'"),
    ],
)
def test_bad_arguments_are_one_line(processes: Any, args: list[str], message: str) -> None:
    proc = demo(processes, 'listener', *args)
    _out, err = proc.communicate(timeout=10)
    assert proc.returncode == 1
    assert err.count('\n') == 1 and message in err


def _env() -> dict[str, str]:
    import os

    return dict(os.environ)


def test_add_two_ints_server_and_clients(processes: Any) -> None:
    server = demo(processes, 'add_two_ints_server')
    for exe, line in (
        ('add_two_ints_client', 'for 2 \\+ 3 = 5'),
        ('add_two_ints_client_async', 'for 41 \\+ 1 = 42'),
    ):
        client = demo(processes, exe)
        out, err = client.communicate(timeout=30)
        assert client.returncode == 0, err
        assert re.search(
            log_line('add_two_ints_client', 'Result of add_two_ints: ' + line), err + out
        ), err + out
    out, err = processes.stop(server)
    assert server.returncode == 0 and 'Traceback' not in err
    assert re.search(
        log_line('add_two_ints_server', 'Incoming request') + '\na: 2 b: 3', err + out
    ), err + out
