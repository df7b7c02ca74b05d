"""Search order, user packages without a build step, and the import hook."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from ros2lite.interfaces import classes, registry
from ros2lite.interfaces.errors import UnknownInterfaceError


def make_pkg(root: Path, pkg: str, files: dict[str, str]) -> None:
    for rel, text in files.items():
        path = root / pkg / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


def test_bundled_packages_are_all_there() -> None:
    reg = registry.Registry([registry.BUNDLED])
    assert len(reg.packages()) == 27  # the reference set, and rosbag2_interfaces for snapshots
    assert len(reg.all_interfaces()) == 239  # and nav_msgs/msg/Goals, rosbag2's Snapshot
    assert 'action_tutorials_interfaces' in reg.packages()
    assert 'turtlesim_msgs' in reg.packages() and 'turtlesim' in reg.packages()


def test_search_order_and_user_package(tmp_path: Path) -> None:
    user, ament = tmp_path / 'user', tmp_path / 'ament'
    make_pkg(user, 'my_pkg', {'msg/Age.msg': 'uint8 years\nstd_msgs/String note\n'})
    # a std_msgs shadowing the bundled one: whole package comes from the first root
    make_pkg(user, 'std_msgs', {'msg/String.msg': 'string data\nint32 extra\n'})
    make_pkg(ament / 'share', 'ament_pkg', {'srv/Ping.srv': 'string q\n---\nstring a\n'})
    reg = registry.Registry([user, ament / 'share', registry.BUNDLED])
    assert reg.package_interfaces('my_pkg') == ['my_pkg/msg/Age']
    assert [f.name for f in reg.message('std_msgs/msg/String').fields] == ['data', 'extra']
    with pytest.raises(UnknownInterfaceError):
        reg.message('std_msgs/msg/Header')  # not in the shadowing package
    assert reg.kind_of('ament_pkg/srv/Ping') == 'service'
    fac = classes.ClassFactory(reg)
    age = fac.message_class('my_pkg/msg/Age')(years=3)
    assert repr(age) == "my_pkg.msg.Age(years=3, note=std_msgs.msg.String(data='', extra=0))"


def test_environment_search_path_in_a_fresh_process(tmp_path: Path) -> None:
    make_pkg(tmp_path / 'ws', 'my_pkg', {'msg/Age.msg': 'uint8 years\n'})
    prefix = tmp_path / 'prefix'
    make_pkg(prefix / 'share', 'other_pkg', {'msg/Point2.msg': 'float64 x\nfloat64 y\n'})
    code = textwrap.dedent("""
        from ros2lite.msgs.my_pkg.msg import Age
        from ros2lite.msgs.other_pkg.msg import Point2
        from ros2lite import interfaces
        print(Age(years=4), Point2(x=1.0))
        print(interfaces.type_hash('my_pkg/msg/Age'))
    """)
    env = {
        'ROS2LITE_INTERFACE_PATH': str(tmp_path / 'ws'),
        'AMENT_PREFIX_PATH': str(prefix),
        'PATH': '/usr/bin:/bin',
    }
    out = subprocess.run(
        [sys.executable, '-c', code], env=env, capture_output=True, text=True, check=True
    ).stdout.splitlines()
    assert out[0] == 'my_pkg.msg.Age(years=4) other_pkg.msg.Point2(x=1.0, y=0.0)'
    assert out[1].startswith('RIHS01_') and len(out[1]) == 71


def test_import_hook_modules() -> None:
    # the modules are built at import time, so static checkers cannot see their names
    from ros2lite.msgs.example_interfaces.action import Fibonacci
    from ros2lite.msgs.example_interfaces.srv import AddTwoInts
    from ros2lite.msgs.std_msgs.msg import String

    assert String(data='x').data == 'x'
    assert AddTwoInts.Request(a=1, b=2).b == 2
    assert Fibonacci.Impl.SendGoalService.Request().goal.order == 0
    import ros2lite.msgs.std_msgs.msg as std

    assert 'Header' in dir(std)
    with pytest.raises(ImportError):
        from ros2lite.msgs.std_msgs.msg import Missing  # type: ignore[attr-defined]  # noqa: F401
    with pytest.raises(ImportError):
        import ros2lite.msgs.no_such_pkg.msg  # noqa: F401


def test_unknown_names() -> None:
    reg = registry.default_registry()
    for name in ('std_msgs/msg/Nope', 'nope/msg/X', 'std_srvs/srv/Empty_Banana'):
        with pytest.raises(UnknownInterfaceError):
            reg.message(name)
