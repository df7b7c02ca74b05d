"""The one reading of the package search path, shared by `run` and the type system."""

from __future__ import annotations

from pathlib import Path

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


def test_the_registry_reads_the_index(tmp_path: Path, monkeypatch: object) -> None:
    import pytest

    assert isinstance(monkeypatch, pytest.MonkeyPatch)
    pkg = tmp_path / 'share' / 'my_msgs' / 'msg'
    pkg.mkdir(parents=True)
    (pkg / 'Age.msg').write_text('uint8 years\n')
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(tmp_path))
    monkeypatch.delenv('ROS2LITE_INTERFACE_PATH', raising=False)
    assert 'my_msgs' in Registry().packages()
