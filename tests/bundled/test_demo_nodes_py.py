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
    return processes.start([sys.executable, '-m', f'ros2lite.bundled.demo_nodes_py.{exe}', *args])


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
        [sys.executable, '-m', 'ros2lite.bundled.demo_nodes_py.talker'],
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
        'start_type_description_service',
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
                "Parameter blackboard node named '/parameter_blackboard' ready, and serving '4' "
                "parameters already!"
            ),
        ),
        err.splitlines()[0],
    ), err


@pytest.mark.parametrize(
    'args, message',
    [
        (['--ros-args', '-r', '__node:=1bad'], "node name '1bad' is invalid"),
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


# -- the rest of Jazzy's demo_nodes_py: same nodes, topics and log lines as ROS's ------------

LOG = re.compile(r'\[(\w+)\] \[\d+\.\d{9}\] \[([\w.]+)\]: (.*)')


def logged(err: str) -> list[tuple[str, str, str]]:
    """(severity, logger, message) of each console log line."""
    return [m.groups() for m in map(LOG.fullmatch, err.splitlines()) if m]  # type: ignore[misc]


def run_to_end(processes: Any, exe: str, *args: str, timeout: float = 60) -> tuple[int, str]:
    proc = processes.cli('run', 'demo_nodes_py', exe, *args)
    _out, err = proc.communicate(timeout=timeout)
    assert 'Traceback' not in err, err
    return proc.returncode, err


def test_pkg_executables_are_jazzys() -> None:
    from ros2lite.pkg.executables import get_executables

    assert [e.name for e in get_executables('demo_nodes_py')] == [
        'add_two_ints_client',
        'add_two_ints_client_async',
        'add_two_ints_server',
        'async_param_client',
        'introspection',
        'listener',
        'listener_qos',
        'listener_serialized',
        'matched_event_detect',
        'set_parameters_callback',
        'talker',
        'talker_qos',
        'use_logger_service',
    ]


def test_talker_qos_and_listener_qos(ros_context: Any, processes: Any) -> None:
    from ros2lite.qos import QoSProfile, ReliabilityPolicy, qos_profile_sensor_data

    node = Node('qos_peer', context=ros_context)
    got: list[str] = []
    node.create_subscription(
        String, 'chatter', lambda m: got.append(m.data), qos_profile_sensor_data
    )
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    talker = processes.cli('run', 'demo_nodes_py', 'talker_qos', '-n', '2')
    spin_until(ex, lambda: got, timeout=15)
    infos = node.get_publishers_info_by_topic('/chatter')
    assert [i.qos_profile.reliability for i in infos] == [ReliabilityPolicy.BEST_EFFORT]
    _out, err = talker.communicate(timeout=15)  # ends by itself after its cycles
    assert talker.returncode == 0 and 'Traceback' not in err
    assert logged(err)[:2] == [
        ('INFO', 'talker_qos', 'Best effort talker'),
        ('INFO', 'talker_qos', 'Publishing: "Hello World: 0"'),
    ]
    assert got[0] == 'Hello World: 0'

    reliable = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE)
    pub = node.create_publisher(String, 'chatter', reliable)
    listener = processes.cli('run', 'demo_nodes_py', 'listener_qos', '--reliable', '-n', '1')
    wait_until(lambda: pub.get_subscription_count() >= 1, timeout=15)
    wait_until(
        lambda: listener.poll() is not None,
        timeout=15,
        step=lambda: pub.publish(String(data='hey')),
    )
    _out, err = listener.communicate()
    assert listener.returncode == 0 and 'Traceback' not in err
    assert logged(err) == [
        ('INFO', 'listener_qos', 'Reliable listener'),
        ('INFO', 'listener_qos', 'I heard: [hey]'),
    ]


def test_listener_serialized_logs_the_cdr_bytes(ros_context: Any, processes: Any) -> None:
    Log = get_interface('rcl_interfaces/msg/Log')
    node = Node('serialized_peer', context=ros_context)
    pub = node.create_publisher(String, 'chatter', 10)
    said: list[Any] = []
    node.create_subscription(Log, '/rosout', said.append, 100)
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    proc = processes.cli('run', 'demo_nodes_py', 'listener_serialized')
    wait_until(lambda: pub.get_subscription_count() >= 1, timeout=15)
    pub.publish(String(data='hi'))
    spin_until(ex, lambda: any(m.name == 'serialized_subscriber' for m in said), timeout=10)
    _out, err = processes.stop(proc)
    assert proc.returncode == 0
    # the CDR of std_msgs/String 'hi' (header, length 3, text, NUL), as Python shows bytes
    line = 'I heard: "b\'\\x00\\x01\\x00\\x00\\x03\\x00\\x00\\x00hi\\x00\'"'
    assert logged(err) == [('INFO', 'serialized_subscriber', line)], err


def test_set_parameters_callback(ros_context: Any, processes: Any) -> None:
    from ros2lite.parameter import Parameter, parameter_value_to_python
    from ros2lite.parameter_client import AsyncParameterClient

    proc = processes.cli('run', 'demo_nodes_py', 'set_parameters_callback')
    client = Node('_callbacks_client', context=ros_context, start_parameter_services=False)
    remote = AsyncParameterClient(client, '/set_parameters_callback')
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(client)

    def wait(future: Any) -> Any:
        executor.spin_until_future_complete(future, 10.0)
        return future.result()

    assert remote.wait_for_services(15.0)
    values = wait(remote.get_parameters(['param1', 'param2'])).values
    assert [parameter_value_to_python(v) for v in values] == [0.0, 0.0]
    # setting param1 brings param2 = 4.0 along (pre-set), and both are accepted (on-set)
    results = wait(remote.set_parameters([Parameter('param1', value=1.5)])).results
    assert results[0].successful
    values = wait(remote.get_parameters(['param1', 'param2'])).values
    assert [parameter_value_to_python(v) for v in values] == [1.5, 4.0]
    # anything else is refused by its on-set callback
    assert (
        not wait(remote.set_parameters([Parameter('use_sim_time', value=True)]))
        .results[0]
        .successful
    )
    processes.stop(proc)
    assert proc.returncode == 0


def test_async_param_client(ros_context: Any, processes: Any) -> None:
    code, err = run_to_end(processes, 'async_param_client')
    assert code == 1  # one line where rclpy's demo raises, then `run`'s own
    assert err.splitlines() == [
        'parameter_blackboard is not available, start parameter blackboard with '
        '`ros2 run demo_nodes_cpp parameter_blackboard` before running this demo',
        '[ros2run]: Process exited with failure 1',
    ]
    board = processes.cli('run', 'demo_nodes_cpp', 'parameter_blackboard')
    # the demo gives the blackboard 3 s, which a busy machine may spend starting it
    wait_for_node(Node('board_watch', context=ros_context), 'parameter_blackboard', timeout=30)
    code, err = run_to_end(processes, 'async_param_client')
    assert code == 0
    said = [
        text for level, name, text in logged(err) if (level, name) == ('INFO', 'async_param_client')
    ]
    set_ok = [f'    {n}:' for n in ('int_parameter', 'bool_parameter', 'string_parameter')]
    assert said == [
        'Setting parameters:',
        set_ok[0], '        successful: True',
        set_ok[1], '        successful: True',
        set_ok[2], '        successful: True',
        'Listing Parameters:',
        '    - int_parameter', '    - bool_parameter', '    - string_parameter',
        'Getting parameters:',
        '    - int_parameter: 10', '    - bool_parameter: False',
        '    - string_parameter: Fee Fi Fo Fum',
        'Loading parameters: ',
        '    other_int_parameter:', '        successful: True', '        value: 0',
        '    int_parameter:', '        successful: True', '        value: 12',
        '    string_parameter:', '        successful: True',
        '        value: I smell the blood of an Englishman',
        '    other_string_parameter:', '        successful: True',
        '        value: One fish, two fish, Red fish, blue fish',
        '    bool_parameter:', '        successful: True', '        value: False',
        'Deleting parameters: ',
        '    other_int_parameter:', '        successful: True', '        reason: ',
        '    other_string_parameter:', '        successful: True', '        reason: ',
        '    string_parameter:', '        successful: True', '        reason: ',
    ]  # fmt: skip
    processes.stop(board)


def test_matched_event_detect(processes: Any) -> None:
    code, err = run_to_end(processes, 'matched_event_detect')
    assert code == 0
    detector = 'matched_event_detection_node'
    counts = 'The changed number of connected {0} is {1} and current number of connected {0} is {2}'
    assert logged(err) == [
        ('INFO', 'multi_sub_node', 'Create a new subscription.'),
        ('INFO', detector, 'First subscription is connected.'),
        ('INFO', 'multi_sub_node', 'Create a new subscription.'),
        ('INFO', detector, counts.format('subscription', 1, 2)),
        ('INFO', 'multi_sub_node', 'Destroy a subscription.'),
        ('INFO', detector, counts.format('subscription', -1, 1)),
        ('INFO', 'multi_sub_node', 'Destroy a subscription.'),
        ('INFO', detector, 'Last subscription is disconnected.'),
        ('INFO', 'multi_pub_node', 'Create a new publisher.'),
        ('INFO', detector, 'First publisher is connected.'),
        ('INFO', 'multi_pub_node', 'Create a new publisher.'),
        ('INFO', detector, counts.format('publisher', 1, 2)),
        ('INFO', 'multi_pub_node', 'Destroy a publisher.'),
        ('INFO', detector, counts.format('publisher', -1, 1)),
        ('INFO', 'multi_pub_node', 'Destroy a publisher.'),
        ('INFO', detector, 'Last publisher is disconnected.'),
    ]


def test_use_logger_service(processes: Any) -> None:
    code, err = run_to_end(processes, 'use_logger_service')
    assert code == 0
    said = [(level, text) for level, _name, text in logged(err)]

    def outputs(n: int, *levels: str) -> list[tuple[str, str]]:
        return [(lv, f'Output {n} with {lv} logger level.') for lv in levels]

    assert said == [
        ('INFO', 'Output with default logger level:'),
        *outputs(1, 'INFO', 'WARN', 'ERROR'),
        ('INFO', 'Current logger level: 0'),  # nothing set for it yet: UNSET
        ('INFO', 'Output with debug logger level:'),
        *outputs(2, 'DEBUG', 'INFO', 'WARN', 'ERROR'),
        ('INFO', 'Current logger level: 10'),
        ('INFO', 'Output with warn logger level:'),
        *outputs(3, 'WARN', 'ERROR'),
        ('INFO', 'Current logger level: 30'),
        ('INFO', 'Output with error logger level:'),
        *outputs(4, 'ERROR'),
        ('INFO', 'Current logger level: 40'),
    ]
