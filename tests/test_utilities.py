"""rclpy's utilities: --ros-args stripped from argv, timeouts as rcl takes them, and the
middleware's name."""

from __future__ import annotations

from ros2lite.utilities import (
    get_rmw_implementation_identifier,
    remove_ros_args,
    timeout_sec_to_nsec,
)


def test_utilities() -> None:
    argv = [
        'prog',
        '-d',
        '--ros-args',
        '-r',
        '__ns:=/a',
        '--',
        '--foo=bar',
        '--ros-args',
        '-p',
        'x:=1',
    ]
    assert remove_ros_args(argv) == ['prog', '-d', '--foo=bar']
    assert timeout_sec_to_nsec(None) < 0 and timeout_sec_to_nsec(-1) < 0
    assert timeout_sec_to_nsec(1.5) == 1_500_000_000 and timeout_sec_to_nsec(0) == 0
    assert get_rmw_implementation_identifier() == 'rmw_zenoh_cpp'
