"""`package.xml`: reading a package's manifest (formats 1 to 3) into plain data.

A manifest found in a workspace is someone else's file: it is parsed with the standard
library's expat (which expands no external entities and limits entity growth), its name is
checked before it is ever used to build a path, and anything malformed is a
:class:`ManifestError` saying which file, which line and why, in one line as colcon does:
not XML, no `<package>` root, a missing or invalid name, no version, no build type.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from .errors import PackageFileError

if TYPE_CHECKING:
    import xml.etree.ElementTree as ET

__all__ = [
    'MANIFEST',
    'Manifest',
    'ManifestError',
    'is_valid_package_name',
    'read_manifest',
]

MANIFEST = 'package.xml'
_MAX_BYTES = 1 << 20  # a manifest is a few KB; refuse to parse anything absurd

# REP 144 asks for lowercase letters, digits and underscores, starting with a letter; older
# packages in the wild also use capitals and dashes, which are still safe in paths
_NAME = re.compile(r'[A-Za-z][A-Za-z0-9_-]*\Z')
_DEPEND_TAGS = (
    'depend',
    'build_depend',
    'build_export_depend',
    'buildtool_depend',
    'buildtool_export_depend',
    'exec_depend',
    'run_depend',
    'test_depend',
    'doc_depend',
)


class ManifestError(PackageFileError):
    """A package.xml that cannot be read or does not describe a package."""


def _line_of(data: bytes, tag: str) -> int | None:
    """The line of the first `<tag` in the file (where to point at a wrong or missing part)."""
    m = re.search(rb'<' + re.escape(tag.encode()) + rb'[\s>/]', data)
    return data.count(b'\n', 0, m.start()) + 1 if m else None


def is_valid_package_name(name: str) -> bool:
    """Is `name` usable as a package name (and so as one path component)?"""
    return bool(_NAME.match(name))


@dataclass(frozen=True)
class Manifest:
    """What ros2lite uses from a package.xml."""

    path: Path
    name: str
    version: str = ''
    description: str = ''
    format: int = 1
    maintainers: tuple[tuple[str, str], ...] = ()  # (name, email)
    licenses: tuple[str, ...] = ()
    build_type: str = 'ament_cmake'
    depends: dict[str, tuple[str, ...]] = field(default_factory=dict)  # tag -> names

    @property
    def directory(self) -> Path:
        """The package's root directory (where package.xml is)."""
        return self.path.parent


def _text(element: ET.Element | None) -> str:
    return ' '.join((element.text or '').split()) if element is not None else ''


def read_manifest(path: Path) -> Manifest:
    """Parse the package.xml at `path`; raises :class:`ManifestError`."""
    # imported here: every process that uses types loads this module, few read a manifest
    import xml.etree.ElementTree as ET

    from ros2lite.util.files import read_bounded

    try:
        data = read_bounded(path, _MAX_BYTES, ValueError, 'a package manifest')
    except ValueError as e:
        raise ManifestError(path, None, str(e)[len(str(path)) + 2 :]) from None
    try:
        root = ET.fromstring(data)
    except ET.ParseError as e:
        line = e.position[0] if e.position else None
        reason = str(e).split(': line ')[0]
        # the package it most likely is, for a lookup by name to find this line
        named = re.search(rb'<name>\s*([A-Za-z][A-Za-z0-9_-]*)\s*</name>', data)
        package = named[1].decode() if named else ''
        raise ManifestError(path, line, f'not valid XML: {reason}', package) from None
    package_line = _line_of(data, root.tag)
    if root.tag != 'package':
        raise ManifestError(path, package_line, f'the root element is <{root.tag}>, not <package>')
    name = _text(root.find('name'))
    if not name:
        raise ManifestError(path, package_line, 'no <name>: a package needs one')
    if not is_valid_package_name(name):
        raise ManifestError(path, _line_of(data, 'name'), f"invalid package name '{name}'")
    try:
        fmt = int(root.get('format', '1'))
    except ValueError:
        raise ManifestError(path, package_line, f"invalid format '{root.get('format')}'") from None
    if not _text(root.find('version')):
        raise ManifestError(path, package_line, f"no <version> for package '{name}'", name)
    build_type = _text(root.find('export/build_type'))
    if not build_type:
        raise ManifestError(
            path,
            _line_of(data, 'export') or package_line,
            f"no <build_type> in <export> for package '{name}' (colcon would take it for a "
            'ROS 1 catkin package): add <build_type>ament_python</build_type>',
            name,
        )
    depends: dict[str, tuple[str, ...]] = {}
    for tag in _DEPEND_TAGS:
        names = tuple(_text(e) for e in root.findall(tag) if _text(e))
        if names:
            depends[tag] = names
    return Manifest(
        path=path,
        name=name,
        version=_text(root.find('version')),
        description=_text(root.find('description')),
        format=fmt,
        maintainers=tuple((_text(m), m.get('email', '')) for m in root.findall('maintainer')),
        licenses=tuple(_text(e) for e in root.findall('license')),
        build_type=build_type,
        depends=depends,
    )
