"""`fetchAsset` through the package index: a robot's mesh served by `package://` and
`file://`, byte for byte, to the protocol's own npm client; anything outside every package's
share folder refused with the protocol's error status, and the bounds around it."""

from __future__ import annotations

import hashlib
import os
import re
from pathlib import Path
from typing import Any

import pytest

from ros2lite.bundled.foxglove_bridge.assets import AssetError, PackageAssets
from ros2lite.bundled.foxglove_bridge.state import DEFAULT_ASSET_ALLOWLIST, compile_patterns
from tests.bundled.test_foxglove_bridge import client_factory, pytestmark, start_bridge

__all__ = ['client_factory', 'pytestmark']


@pytest.fixture
def robot(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> dict[str, Path]:
    """An ament prefix holding `fox_robot` (a mesh, a link out, a FIFO), and a secret next
    to it outside any package."""
    prefix = tmp_path / 'install'
    (prefix / 'share' / 'ament_index' / 'resource_index' / 'packages').mkdir(parents=True)
    (prefix / 'share' / 'ament_index' / 'resource_index' / 'packages' / 'fox_robot').touch()
    share = prefix / 'share' / 'fox_robot'
    (share / 'meshes').mkdir(parents=True)
    (share / 'package.xml').write_text('<package format="3"><name>fox_robot</name></package>')
    mesh = share / 'meshes' / 'base link.stl'
    mesh.write_bytes(b'solid fox\n' + os.urandom(50_000) + b'endsolid fox\n')
    secret = tmp_path / 'secret.stl'
    secret.write_bytes(b'not for clients')
    (share / 'meshes' / 'escape.stl').symlink_to(secret)
    os.mkfifo(share / 'meshes' / 'pipe.stl')
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(prefix))
    return {'share': share, 'mesh': mesh, 'secret': secret}


def _assets(limit: int = 1 << 20) -> PackageAssets:
    allowlist = compile_patterns(DEFAULT_ASSET_ALLOWLIST, 'asset_uri_allowlist')
    return PackageAssets(allowlist, limit=limit)


def test_only_share_folders_are_served(robot: dict[str, Path]) -> None:
    assets = _assets()
    mesh = robot['mesh'].read_bytes()
    assert assets.fetch('package://fox_robot/meshes/base%20link.stl') == mesh
    assert assets.fetch(f'file://{robot["share"]}/meshes/base%20link.stl') == mesh
    refused = {
        'package://fox_robot/../../../secret.stl': 'not allowed',
        'package://fox_robot/%2e%2e/%2E%2E/%2e%2e/secret.stl': 'Refused path',
        'package://fox_robot/meshes/escape.stl': 'outside the package share folders',
        f'file://{robot["secret"]}': 'outside the package share folders',
        f'file://{robot["share"]}/../../../secret.stl': 'Refused path',
        'package://fox_robot/meshes/pipe.stl': 'Not a regular file',
        'package://no_such_pkg/meshes/a.stl': "Package 'no_such_pkg' not found",
        'package://fox_robot/package.xml': 'not allowed',  # not a mesh or texture
        'file:///etc/passwd': 'not allowed',
        'http://example.com/a.stl': 'not allowed',
        'package://fox_robot/meshes/none.stl': 'Asset not found',
    }
    for uri, why in refused.items():
        with pytest.raises(AssetError, match=re.escape(why)):
            assets.fetch(uri)
    with pytest.raises(AssetError, match='too large'):
        _assets(limit=1000).fetch('package://fox_robot/meshes/base%20link.stl')


def test_npm_client_fetches_a_mesh_and_is_refused_outside(
    robot: dict[str, Path], processes: Any, client_factory: Any
) -> None:
    _, port, _ = start_bridge(processes)
    client = client_factory(port)
    info = client.expect(lambda e: e['event'] == 'serverInfo')['info']
    assert 'assets' in info['capabilities']
    mesh = robot['mesh'].read_bytes()
    uris = {
        1: 'package://fox_robot/meshes/base%20link.stl',
        2: f'file://{robot["share"]}/meshes/base%20link.stl',
        3: f'file://{robot["secret"]}',
        4: 'package://fox_robot/meshes/escape.stl',
        5: 'package://fox_robot/../../../secret.stl',
    }
    for request_id, uri in uris.items():
        client.send(cmd='fetchAsset', uri=uri, id=request_id)
    answers = {}
    while len(answers) < len(uris):
        ev = client.expect(lambda e: e['event'] == 'asset')
        answers[ev['id']] = ev
    for request_id in (1, 2):
        assert answers[request_id]['status'] == 0, answers[request_id]
        assert answers[request_id]['length'] == len(mesh)
        assert answers[request_id]['sha256'] == hashlib.sha256(mesh).hexdigest()
    for request_id in (3, 4, 5):
        assert answers[request_id]['status'] == 1, answers[request_id]  # the protocol's error
        assert answers[request_id]['error'], answers[request_id]
    assert 'outside the package share folders' in answers[3]['error']
