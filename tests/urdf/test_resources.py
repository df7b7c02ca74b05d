"""resolve_resource: `package://` and `file://` URIs to files inside package share folders
only, through the package index (the Foxglove bridge's fetchAsset tests cover it end to end)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from ros2lite.pkg.index import PackageIndex
from ros2lite.urdf import UrdfError, resolve_resource
from ros2lite.urdf.resources import ResourceResolver


@pytest.fixture
def share(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    prefix = tmp_path / 'install'
    marker = prefix / 'share' / 'ament_index' / 'resource_index' / 'packages'
    marker.mkdir(parents=True)
    (marker / 'arm_description').touch()
    share = prefix / 'share' / 'arm_description'
    (share / 'meshes').mkdir(parents=True)
    (share / 'package.xml').write_text('<package format="3"><name>arm_description</name></package>')
    (share / 'meshes' / 'fore arm.stl').write_bytes(b'solid arm\nendsolid arm\n')
    (tmp_path / 'secret').write_text('no')
    (share / 'meshes' / 'out.stl').symlink_to(tmp_path / 'secret')
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(prefix))
    return share


def test_uris_resolve_inside_share_folders_only(share: Path) -> None:
    resolver = ResourceResolver(PackageIndex())
    mesh = share.resolve() / 'meshes' / 'fore arm.stl'
    assert resolver.resolve('package://arm_description/meshes/fore%20arm.stl') == mesh
    assert resolver.resolve(f'file://{share}/meshes/fore arm.stl') == mesh
    refused = {
        'package://arm_description/meshes/out.stl': 'outside the package share folders',
        f'file://{share.parent.parent.parent}/secret': 'outside the package share folders',
        'package://arm_description/../../x': 'Refused path',
        'package://arm_description/%2e%2e/x': 'Refused path',
        'package://no_pkg/a.stl': "Package 'no_pkg' not found",
        'package://a%20b/a.stl': 'Not a package name',
        'file://relative/a.stl': 'Only absolute file://',
        'http://example.com/a.stl': 'Unsupported resource URI scheme',
        'package://arm_description/' + 'a' * 5000: 'too long',
    }
    for uri, why in refused.items():
        with pytest.raises(UrdfError, match=why):
            resolver.resolve(uri)
    with pytest.raises(FileNotFoundError, match='Resource not found'):
        resolver.resolve('package://arm_description/meshes/none.stl')


def test_the_module_function_uses_the_environment_index(share: Path) -> None:
    found = resolve_resource('package://arm_description/package.xml')
    assert found == share.resolve() / 'package.xml'
    assert os.path.isfile(found)
