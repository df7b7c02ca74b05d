"""`service call` to a name served with another type says so instead of waiting in silence."""

from __future__ import annotations

from typing import Any

from tests.cli.conftest import run_process


def test_call_says_the_type_the_service_has(adder: Any) -> None:
    result = run_process('service', 'call', '/math/add', 'std_srvs/srv/Trigger', '--timeout', '3')
    assert result.code == 1
    assert (
        "WARNING: service '/math/add' is served as example_interfaces/srv/AddTwoInts, not "
        'std_srvs/srv/Trigger; nothing will answer until a server of std_srvs/srv/Trigger '
        'appears\n'
    ) in result.err
    assert result.err.endswith("Timed out after 3 s waiting for service '/math/add'\n")


def test_a_kilted_name_at_a_jazzy_turtlesim_names_ros_distro(ros_context: Any) -> None:
    """A Kilted course's `turtlesim_msgs/srv/Spawn` at Jazzy's turtlesim (`turtlesim/srv/
    Spawn`, the default): the warning says what ROS_DISTRO=kilted would change."""
    from ros2lite.interfaces import get_interface
    from ros2lite.node import Node

    node = Node('jazzy_turtlesim', context=ros_context, enable_rosout=False)
    try:
        node.create_service(get_interface('turtlesim/srv/Spawn'), '/spawn_j', lambda q, r: r)
        result = run_process(
            'service', 'call', '/spawn_j', 'turtlesim_msgs/srv/Spawn', '--timeout', '3'
        )
        assert result.code == 1
        assert (
            "WARNING: service '/spawn_j' is served as turtlesim/srv/Spawn, not "
            'turtlesim_msgs/srv/Spawn; nothing will answer until a server of '
            "turtlesim_msgs/srv/Spawn appears (turtlesim_msgs is Kilted's name for these "
            'interfaces: start the node with ROS_DISTRO=kilted to serve it, or type '
            'turtlesim/srv/Spawn)\n'
        ) in result.err
    finally:
        node.destroy_node()
