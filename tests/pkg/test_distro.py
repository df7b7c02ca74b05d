"""Jazzy unless ROS_DISTRO names a distro ros2lite speaks."""

from __future__ import annotations

import pytest

from ros2lite.pkg.distro import ros_distro, turtlesim_interfaces


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
