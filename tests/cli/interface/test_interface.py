"""`ros2lite interface …` output, formats and errors as ros2cli prints them."""

from __future__ import annotations

from collections.abc import Callable

from ros2lite import interfaces

from ..conftest import Result, run_process

Run = Callable[..., Result]


def test_list_sections(run: Run) -> None:
    out = run('interface', 'list').out.splitlines()
    assert out[0] == 'Messages:' and out[1] == '    action_msgs/msg/GoalInfo'
    assert 'Services:' in out and 'Actions:' in out
    assert '    example_interfaces/action/Fibonacci' in out
    assert len(out) == 3 + len(interfaces.list_interfaces())
    only = run('interface', 'list', '-s', '-a').out.splitlines()
    assert only[0] == 'Services:' and 'Messages:' not in only


def test_packages_and_package(run: Run) -> None:
    packages = run('interface', 'packages').out.splitlines()
    assert len(packages) == 27 and packages == sorted(packages)
    assert run('interface', 'packages', '-a').out.split() == [
        'action_tutorials_interfaces',
        'example_interfaces',
        'tf2_msgs',
        'turtlesim',
        'turtlesim_msgs',
    ]
    assert run('interface', 'package', 'std_srvs').out.split() == [
        'std_srvs/srv/Empty',
        'std_srvs/srv/SetBool',
        'std_srvs/srv/Trigger',
    ]
    # ros2cli's grouping: messages, then services, then actions, whatever the flags' order
    assert run('interface', 'package', 'turtlesim', '-a', '-m').out.split() == [
        'turtlesim/msg/Color',
        'turtlesim/msg/Pose',
        'turtlesim/action/RotateAbsolute',
    ]
    assert run('interface', 'package', 'turtlesim').out.split()[-1] == (
        'turtlesim/action/RotateAbsolute'
    )
    bad = run('interface', 'package', 'nope')
    assert bad.code == 1 and bad.err == "Unknown package 'nope'\n"


def test_show(run: Run) -> None:
    assert (
        run('interface', 'show', 'example_interfaces/action/Fibonacci').out
        == 'int32 order\n---\nint32[] sequence\n---\nint32[] sequence\n'
    )
    out = run('interface', 'show', 'geometry_msgs/msg/Twist').out
    assert out == (
        'Vector3  linear\n\tfloat64 x\n\tfloat64 y\n\tfloat64 z\n'
        'Vector3  angular\n\tfloat64 x\n\tfloat64 y\n\tfloat64 z\n'
    )
    assert run('interface', 'show', 'std_msgs/msg/Empty').out == ''  # as ros2cli: no blank line
    bad = run('interface', 'show', 'std_msgs/String')
    assert bad.code == 1
    assert bad.err == "Invalid name 'std_msgs/String'. Expected three parts separated by '/'\n"


def test_show_reads_type_from_pipe() -> None:
    result = run_process('interface', 'show', '-', stdin='std_msgs/msg/Bool\n')
    assert result.code == 0 and result.out == 'bool data\n'


def test_proto(run: Run) -> None:
    assert (
        run('interface', 'proto', 'geometry_msgs/msg/Vector3').out == '"x: 0.0\ny: 0.0\nz: 0.0\n"\n'
    )
    assert (
        run('interface', 'proto', 'example_interfaces/srv/AddTwoInts', '--no-quotes').out
        == 'a: 0\nb: 0\n\n'
    )
    assert run('interface', 'proto', 'example_interfaces/action/Fibonacci').out == '"order: 0\n"\n'


def test_hash(run: Run) -> None:
    assert (
        run('interface', 'hash', 'std_msgs/msg/String').out
        == 'RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18\n'
    )
    bad = run('interface', 'hash', 'std_msgs/msg/Nope')
    assert bad.code == 1 and bad.err == "Unknown interface 'std_msgs/msg/Nope'\n"
