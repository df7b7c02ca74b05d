"""package.xml reading: the fields ros2lite uses, and what it refuses."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite.pkg.manifest import ManifestError, is_valid_package_name, read_manifest
from tests.pkg.workspaces import write_package


def test_fields(tmp_path: Path) -> None:
    write_package(tmp_path, 'my_pkg', depends=('rclpy', 'std_msgs'))
    m = read_manifest(tmp_path / 'package.xml')
    assert (m.name, m.version, m.format, m.build_type) == ('my_pkg', '1.2.3', 3, 'ament_python')
    assert m.maintainers == (('Maint', 'm@example.com'),)
    assert m.licenses == ('Apache-2.0',)
    assert m.depends == {'depend': ('rclpy', 'std_msgs')}
    assert m.directory == tmp_path


@pytest.mark.parametrize(
    ('content', 'error'),
    [
        ('<package><name>x', 'not valid XML'),
        ('<launch/>', 'the root element is <launch>'),
        (
            '<package format="3"><name>../../etc</name></package>',
            "invalid package name '../../etc'",
        ),
        ('<package format="3"></package>', "invalid package name ''"),
        ('<package format="x"><name>a</name></package>', "invalid format 'x'"),
    ],
)
def test_bad_manifests(tmp_path: Path, content: str, error: str) -> None:
    (tmp_path / 'package.xml').write_text(content)
    with pytest.raises(ManifestError, match=error.replace('(', r'\(').replace('.', r'\.')):
        read_manifest(tmp_path / 'package.xml')


def test_entities_are_not_expanded(tmp_path: Path) -> None:
    # a classic entity bomb: expat refuses it instead of growing without bound
    bomb = (
        '<?xml version="1.0"?><!DOCTYPE p [<!ENTITY a "aaaaaaaaaa">'
        + ''.join(
            f'<!ENTITY {c} "&{p};&{p};&{p};&{p};&{p};&{p};&{p};&{p};&{p};&{p};">'
            for p, c in zip('abcdefgh', 'bcdefghi', strict=True)
        )
        + ']><package><name>&i;</name></package>'
    )
    (tmp_path / 'package.xml').write_text(bomb)
    with pytest.raises(ManifestError):
        read_manifest(tmp_path / 'package.xml')


def test_default_build_type_and_names() -> None:
    assert is_valid_package_name('py_pubsub') and is_valid_package_name('Old-Style')
    assert not is_valid_package_name('1abc') and not is_valid_package_name('a/b')
