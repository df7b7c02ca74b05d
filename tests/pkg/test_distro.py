"""Jazzy unless ROS_DISTRO names a distro ros2lite speaks."""

from __future__ import annotations

import pytest

from ros2lite.pkg.distro import other_distro_name, ros_distro, turtlesim_interfaces


@pytest.mark.parametrize(
    ('value', 'distro'),
    [
        (None, 'jazzy'),
        ('', 'jazzy'),
        ('jazzy', 'jazzy'),
        ('kilted', 'kilted'),
        (' Kilted\n', 'kilted'),
        ('rolling', 'rolling'),
        ('humble', 'jazzy'),  # not one we speak: the default
    ],
)
def test_the_distro_comes_from_ros_distro(value: str | None, distro: str) -> None:
    env = {} if value is None else {'ROS_DISTRO': value}
    assert ros_distro(env) == distro


def test_turtlesim_interfaces_moved_after_jazzy() -> None:
    assert turtlesim_interfaces('jazzy') == 'turtlesim'
    assert turtlesim_interfaces('kilted') == 'turtlesim_msgs'
    assert turtlesim_interfaces('rolling') == 'turtlesim_msgs'


def test_a_name_of_the_other_distro_is_explained() -> None:
    """The line a warning adds when a course's name meets a node of the other distro."""
    kilted_name = other_distro_name('turtlesim_msgs/srv/Spawn', ['turtlesim/srv/Spawn'])
    assert kilted_name == (
        "turtlesim_msgs is Kilted's name for these interfaces: start the node with "
        'ROS_DISTRO=kilted to serve it, or type turtlesim/srv/Spawn'
    )
    jazzy_name = other_distro_name('turtlesim/msg/Pose', ['turtlesim_msgs/msg/Pose'])
    assert 'runs with ROS_DISTRO=kilted' in jazzy_name and 'turtlesim_msgs/msg/Pose' in jazzy_name
    assert other_distro_name('turtlesim_msgs/srv/Kill', ['turtlesim/srv/Spawn']) == ''
    assert other_distro_name('std_msgs/msg/String', ['std_msgs/msg/Int32']) == ''
