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


_EXPORT = '<export><build_type>ament_python</build_type></export>'


@pytest.mark.parametrize(
    ('content', 'error'),
    [
        ('<package>\n<name>x', '2: not valid XML: no element found'),
        (
            '<?xml version="1.0"?>\n<package>\n <name>x</nam>\n</package>',
            '3: not valid XML: mismatched tag',
        ),
        ('<launch/>', '1: the root element is <launch>, not <package>'),
        (
            '<package format="3">\n<name>../../etc</name></package>',
            "2: invalid package name '../../etc'",
        ),
        (
            '<?xml version="1.0"?>\n<package format="3"></package>',
            '2: no <name>: a package needs one',
        ),
        ('<package format="x"><name>a</name></package>', "1: invalid format 'x'"),
        (
            f'<package format="3">\n  <name>a</name>\n  {_EXPORT}\n</package>',
            "1: no <version> for package 'a'",
        ),
        (
            '<package format="3">\n  <name>a</name>\n  <version>1.0.0</version>\n</package>',
            "1: no <build_type> in <export> for package 'a' (colcon would take it for a ROS 1 "
            'catkin package): add <build_type>ament_python</build_type>',
        ),
    ],
)
def test_bad_manifests_name_file_and_line(tmp_path: Path, content: str, error: str) -> None:
    """One line each, `file:line: what is wrong`, as colcon names a package.xml it refuses."""
    (tmp_path / 'package.xml').write_text(content)
    with pytest.raises(ManifestError) as caught:
        read_manifest(tmp_path / 'package.xml')
    assert str(caught.value) == f'{tmp_path / "package.xml"}:{error}'


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
