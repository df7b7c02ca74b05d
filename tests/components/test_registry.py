"""Where components come from: bundled, entry points, the ament index (Python and C++), in
that precedence, and what loading them says when it cannot."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

from ros2lite.components.registry import (
    ComponentLoadError,
    component_types,
    find_component,
    load_class,
)


def ament_prefix(root: Path, resource: str, package: str, lines: list[str]) -> Path:
    index = root / 'share' / 'ament_index' / 'resource_index'
    (index / 'packages').mkdir(parents=True, exist_ok=True)
    (index / 'packages' / package).write_text('')
    (index / resource).mkdir(parents=True, exist_ok=True)
    (index / resource / package).write_text('\n'.join(lines) + '\n')
    return root


def test_bundled_composition_components() -> None:
    types = component_types(env={})
    assert [t.plugin for t in types['composition']] == [
        'composition::Talker',
        'composition::Listener',
        'composition::Server',
        'composition::Client',
    ]
    talker = load_class(find_component('composition', 'composition::Talker', env={}))
    assert talker.__name__ == 'Talker'


def test_unknown_names_get_rclcpp_words() -> None:
    with pytest.raises(ComponentLoadError, match='Could not find requested resource in ament'):
        find_component('no_such_package', 'x::Y', env={})
    with pytest.raises(ComponentLoadError, match='Failed to find class with the requested'):
        find_component('composition', 'composition::Nope', env={})


def test_ament_index_python_and_cpp(tmp_path: Path) -> None:
    site = tmp_path / 'ws' / 'lib' / f'python{sys.version_info.major}.{sys.version_info.minor}'
    (site / 'site-packages' / 'ws_pkg').mkdir(parents=True)
    (site / 'site-packages' / 'ws_pkg' / '__init__.py').write_text(
        'class Thing:\n    """A workspace component."""\n'
    )
    ament_prefix(
        tmp_path / 'ws',
        'rclpy_components',
        'ws_pkg',
        ['ws_pkg::Thing;ws_pkg:Thing', 'malformed line', '', 'ws_pkg::Gone;ws_pkg:Gone'],
    )
    ament_prefix(
        tmp_path / 'opt',
        'rclcpp_components',
        'composition',
        ['composition::Talker;lib/libtalker.so'],
    )
    ament_prefix(tmp_path / 'opt', 'rclcpp_components', 'cpp_only', ['cpp_only::Node;lib/x.so'])
    env = {'AMENT_PREFIX_PATH': f'{tmp_path / "ws"}:{tmp_path / "opt"}'}
    types = component_types(env=env)
    assert [t.plugin for t in types['ws_pkg']] == ['ws_pkg::Thing', 'ws_pkg::Gone']
    # an installed C++ package shadows the bundled one of the same name, as overlays do
    assert [t.target for t in types['composition']] == ['lib/libtalker.so']
    thing = find_component('ws_pkg', 'ws_pkg::Thing', env=env)
    try:
        assert load_class(thing).__doc__ == 'A workspace component.'  # its site-packages joined
    finally:
        sys.path.remove(str(site / 'site-packages'))
        sys.modules.pop('ws_pkg', None)
    with pytest.raises(ComponentLoadError, match=r"cannot import 'ws_pkg:Gone'.*AttributeError"):
        load_class(find_component('ws_pkg', 'ws_pkg::Gone', env=env))
    with pytest.raises(ComponentLoadError, match=r"is a C\+\+ component .*rclcpp_components"):
        load_class(find_component('cpp_only', 'cpp_only::Node', env=env))


def test_entry_points_come_first(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    dist = tmp_path / 'probe_components-1.0.dist-info'
    dist.mkdir()
    (dist / 'METADATA').write_text('Metadata-Version: 2.1\nName: probe-components\nVersion: 1.0\n')
    (dist / 'entry_points.txt').write_text(
        '[ros2lite.components]\n'
        'composition.composition::Probe = tests.components.probe:Probe\n'
        'nodot = tests.components.probe:Probe\n'
    )
    monkeypatch.syspath_prepend(str(tmp_path))
    types = component_types(env={})
    # the package is owned by the entry points now: the bundled composition is hidden
    assert [t.plugin for t in types['composition']] == ['composition::Probe']
    assert 'nodot' not in types
    assert load_class(find_component('composition', 'composition::Probe', env={})).__name__ == (
        'Probe'
    )
