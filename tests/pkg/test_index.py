"""The one reading of the package search path, shared by `run` and the type system."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite.interfaces.registry import Registry
from ros2lite.pkg.index import BUNDLED_INTERFACES, ament_prefixes, interface_roots


def test_interface_roots_in_priority_order(tmp_path: Path) -> None:
    env = {
        'ROS2LITE_INTERFACE_PATH': f'{tmp_path / "mine"}:',
        'AMENT_PREFIX_PATH': f'{tmp_path / "ws"}:{tmp_path / "opt"}',
    }
    assert ament_prefixes(env) == [tmp_path / 'ws', tmp_path / 'opt']
    assert interface_roots(env) == [
        tmp_path / 'mine',
        tmp_path / 'ws' / 'share',
        tmp_path / 'opt' / 'share',
        BUNDLED_INTERFACES,
    ]
    assert interface_roots({}) == [BUNDLED_INTERFACES]


def test_the_registry_reads_the_index(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    pkg = tmp_path / 'share' / 'my_msgs' / 'msg'
    pkg.mkdir(parents=True)
    (pkg / 'Age.msg').write_text('uint8 years\n')
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(tmp_path))
    monkeypatch.delenv('ROS2LITE_INTERFACE_PATH', raising=False)
    assert 'my_msgs' in Registry().packages()


def _ament_package(prefix: Path, name: str, *, msgs: dict[str, str] | None = None) -> None:
    marker = prefix / 'share' / 'ament_index' / 'resource_index' / 'packages'
    marker.mkdir(parents=True, exist_ok=True)
    (marker / name).write_text('')
    for file, text in (msgs or {}).items():
        path = prefix / 'share' / name / 'msg' / file
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


def test_precedence_and_ownership(tmp_path: Path) -> None:
    from ros2lite.pkg.index import PackageIndex
    from tests.pkg.workspaces import write_package

    ws = tmp_path / 'ws'
    write_package(ws / 'src' / 'shared', 'shared')  # no msg/: the workspace owns it anyway
    write_package(ws / 'src' / 'turtlesim', 'turtlesim')
    opt = tmp_path / 'opt'
    _ament_package(opt, 'shared', msgs={'Old.msg': 'int32 x\n'})
    _ament_package(opt, 'only_installed')
    index = PackageIndex({'AMENT_PREFIX_PATH': str(opt)}, cwd=ws / 'src')
    assert [p.origin for p in index.candidates('shared')] == ['workspace', 'ament']
    assert [p.origin for p in index.candidates('turtlesim')] == ['workspace', 'bundled']
    found = index.find('only_installed')
    assert found is not None and found.prefix == opt
    assert found.share == opt / 'share' / 'only_installed'
    # a package is never merged: the workspace's 'shared' has no interfaces
    assert 'shared' not in index.interface_packages()
    assert index.find('std_msgs') is not None and index.find('std_msgs').origin == 'bundled'
    names = list(index.packages())
    assert names == sorted(names) and {'shared', 'turtlesim', 'std_msgs'} <= set(names)


def test_workspace_interfaces_reach_the_type_system(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """An ament_cmake interface package in a workspace, used by another package's type."""
    from ros2lite.interfaces.classes import get_interface
    from tests.pkg.workspaces import write_package

    ws = tmp_path / 'ws'
    iface = write_package(
        ws / 'src' / 'tutorial_interfaces', 'tutorial_interfaces', build_type='ament_cmake'
    )
    (iface / 'msg').mkdir()
    (iface / 'msg' / 'Age.msg').write_text('uint8 years\nuint8 months\n')
    other = write_package(ws / 'src' / 'people', 'people', build_type='ament_cmake')
    (other / 'msg').mkdir()
    (other / 'msg' / 'Person.msg').write_text('string name\ntutorial_interfaces/Age age\n')
    monkeypatch.chdir(ws / 'src' / 'people')
    monkeypatch.delenv('ROS2LITE_INTERFACE_PATH', raising=False)
    reg = Registry()
    assert reg.packages()['tutorial_interfaces'] == iface
    assert reg.package_interfaces('people') == ['people/msg/Person']
    person = reg.message('people/msg/Person')
    assert [f.name for f in person.fields] == ['name', 'age']
    age = get_interface('tutorial_interfaces/msg/Age', reg)
    assert age(years=3).years == 3


def test_the_python_environment_is_a_source_of_its_own(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """Interface packages installed into the interpreter's prefix (ROS's PyPI wheels) are
    found with no variable set, after AMENT_PREFIX_PATH and before the bundled copies; a
    name ros2lite bundles a demo for stays bundled, and non-interface packages stay out."""
    from ros2lite.pkg import index as index_module
    from ros2lite.pkg.index import PackageIndex

    venv = tmp_path / 'venv'
    _ament_package(venv, 'std_msgs', msgs={'Bool.msg': '# documented\nbool data\n'})
    _ament_package(venv, 'turtlesim', msgs={'Pose.msg': 'float32 x\n'})
    _ament_package(venv, 'rosidl_cmake')  # build tooling: no interfaces
    opt = tmp_path / 'opt'
    _ament_package(opt, 'std_msgs', msgs={'Bool.msg': 'bool data\n'})
    monkeypatch.setattr(index_module, '_environment', [venv])
    assert interface_roots({})[-2:] == [venv / 'share', BUNDLED_INTERFACES]
    index = PackageIndex({}, cwd=tmp_path)
    assert [p.origin for p in index.candidates('std_msgs')] == ['environment', 'bundled']
    assert index.interface_packages()['std_msgs'] == venv / 'share' / 'std_msgs'
    assert index.find('turtlesim').origin == 'bundled'  # type: ignore[union-attr]
    assert index.find('rosidl_cmake') is None
    over = PackageIndex({'AMENT_PREFIX_PATH': str(opt)}, cwd=tmp_path)
    assert [p.origin for p in over.candidates('std_msgs')] == ['ament', 'environment', 'bundled']
