"""Shell completion: names from the live graph and the local index, nothing (and fast) when
no router answers, and the bash/zsh activation scripts click generates for us."""

from __future__ import annotations

import time
from typing import Any

from ros2lite.node import Node
from tests.spinning import free_port

from .conftest import run_process


def complete(words: str, env: dict[str, str] | None = None) -> list[str]:
    """What `ros2lite` offers for the last word of `words`, as the bash hook would ask."""
    result = run_process(
        env={
            **(env or {}),
            '_ROS2LITE_COMPLETE': 'bash_complete',
            'COMP_WORDS': words,
            'COMP_CWORD': str(len(words.split(' ')) - 1),
        }
    )
    assert (result.code, result.err) == (0, '')
    return [line.split(',', 1)[1] for line in result.out.splitlines() if line]


def test_topics_and_nodes_come_from_the_live_graph(ros_context: Any) -> None:
    node = Node('completion_probe', namespace='/cmp', context=ros_context, enable_rosout=False)
    try:
        node.create_publisher('std_msgs/msg/String', 'cmp_chatter', 10)
        node.create_publisher('std_msgs/msg/String', '_cmp_hidden', 10)
        assert complete('ros2lite topic echo /cmp/cmp_') == ['/cmp/cmp_chatter']
        assert complete('ros2lite topic hz /cmp/cmp_chatter /cmp/cmp_') == ['/cmp/cmp_chatter']
        # hidden names only once the user has started typing one
        assert '/cmp/_cmp_hidden' not in complete('ros2lite topic info /cmp/')
        assert complete('ros2lite topic info /cmp/_') == ['/cmp/_cmp_hidden']
        assert complete('ros2lite node info /cmp/comp') == ['/cmp/completion_probe']
    finally:
        node.destroy_node()


def test_services_and_actions_come_from_the_live_graph(ros_context: Any) -> None:
    from ros2lite.action import ActionServer
    from ros2lite.msgs.action_tutorials_interfaces.action import Fibonacci
    from ros2lite.msgs.example_interfaces.srv import AddTwoInts

    node = Node(
        'completion_services',
        namespace='/cmps',
        context=ros_context,
        enable_rosout=False,
        start_parameter_services=False,
    )
    try:
        node.create_service(AddTwoInts, 'cmp_add', lambda req, resp: resp)
        server = ActionServer(node, Fibonacci, 'cmp_fib', lambda goal: Fibonacci.Result())
        assert complete('ros2lite service call /cmps/cmp_') == ['/cmps/cmp_add']
        assert complete('ros2lite action send_goal /cmps/cmp_') == ['/cmps/cmp_fib']
        assert 'example_interfaces/srv/AddTwoInts' in complete(
            'ros2lite service call /cmps/cmp_add example_interfaces/srv/Add'
        )
        server.destroy()
    finally:
        node.destroy_node()


def test_types_packages_and_executables() -> None:
    assert complete('ros2lite topic pub /x geometry_msgs/msg/Twist') == [
        'geometry_msgs/msg/Twist',
        'geometry_msgs/msg/TwistStamped',
        'geometry_msgs/msg/TwistWithCovariance',
        'geometry_msgs/msg/TwistWithCovarianceStamped',
    ]
    assert complete('ros2lite topic find std_srvs/') == []  # services are not topics
    assert 'std_srvs/srv/SetBool' in complete('ros2lite interface show std_srvs/')
    assert complete('ros2lite interface package geometry_') == ['geometry_msgs']
    assert complete('ros2lite run demo_nodes_') == ['demo_nodes_py']
    assert complete('ros2lite run demo_nodes_py ') == [
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
    assert complete('ros2lite run no_such_pkg ') == []
    assert complete('ros2lite top') == ['topic']


def test_option_names_and_values() -> None:
    """Option names complete wherever a word starts with '-' (the parser tells click's
    completion its option prefixes), and an option's value gets the option's completer."""
    assert complete('ros2lite topic echo --qos-d') == ['--qos-depth', '--qos-durability']
    assert complete('ros2lite --rou') == ['--router']
    assert complete('ros2lite bag play x --clo') == ['--clock']
    assert '-1' in complete('ros2lite topic pub -')
    assert complete('ros2lite topic echo --qos-profile sensor_') == ['sensor_data']


def test_no_router_completes_nothing_quickly() -> None:
    nobody = {'ROS2LITE_ROUTER': f'tcp/127.0.0.1:{free_port()}'}
    start = time.monotonic()
    assert complete('ros2lite topic echo /', nobody) == []
    assert time.monotonic() - start < 10
    # and it did not start a daemon on that endpoint
    assert 'not running' in run_process('daemon', 'status', env=nobody).out


def test_activation_scripts() -> None:
    for shell in ('bash', 'zsh'):
        result = run_process(env={'_ROS2LITE_COMPLETE': f'{shell}_source'})
        assert result.code == 0
        assert '_ROS2LITE_COMPLETE' in result.out and 'ros2lite' in result.out


def test_packages_executables_and_launch_files_from_the_index() -> None:
    assert complete('ros2lite launch demo_nodes_py talker') == [
        'talker_listener.launch.py',
        'talker_listener.launch.xml',
        'talker_listener.launch.yaml',
    ]
    assert complete('ros2lite run turtlesim turtle_tel') == ['turtle_teleop_key']
    assert complete('ros2lite pkg prefix demo_nodes_p') == ['demo_nodes_py']
