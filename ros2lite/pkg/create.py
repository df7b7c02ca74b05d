"""`pkg create`: a new package on disk, laid out as `ros2 pkg create` lays it out.

The result builds with real colcon on a ROS machine and, for ament_python, runs at once with
`ros2lite run` (the package index reads its sources). Names are checked before they become
paths or code; files are created fresh (an existing file or symlink is never written through).
"""

from __future__ import annotations

import getpass
import os
import re
import shutil
import subprocess
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path

from ros2lite.exceptions import Ros2liteError
from ros2lite.util.files import create_new

from . import templates
from .templates import PackageSpec

__all__ = [
    'BUILD_TYPES',
    'LICENSES',
    'CreateError',
    'Created',
    'PackageSpec',
    'create_package',
    'default_maintainer',
    'prepare_spec',
]

BUILD_TYPES = ('cmake', 'ament_cmake', 'ament_python')

# the license identifiers ament_copyright knows, in its order, and the texts written for them
LICENSES = (
    'Apache-2.0',
    'BSL-1.0',
    'BSD-2.0',
    'BSD-2-Clause',
    'BSD-3-Clause',
    'GPL-3.0-only',
    'LGPL-3.0-only',
    'MIT',
    'MIT-0',
)
_LICENSE_TEXTS = {
    'Apache-2.0': ('Apache-2.0.txt',),
    'BSL-1.0': ('BSL-1.0.txt',),
    'BSD-2.0': ('BSD-2-Clause.txt',),
    'BSD-2-Clause': ('BSD-2-Clause.txt',),
    'BSD-3-Clause': ('BSD-3-Clause.txt',),
    'GPL-3.0-only': ('GPL-3.0-only.txt',),
    # the LGPL is a set of permissions on top of the GPL: both texts go in
    'LGPL-3.0-only': ('LGPL-3.0-only.txt', 'GPL-3.0-only.txt'),
    'MIT': ('MIT.txt',),
    'MIT-0': ('MIT-0.txt',),
}
_LICENSE_DIR = Path(__file__).resolve().parent / 'licenses'

# REP 144: lowercase letters, digits and underscores, starting with a letter
_PACKAGE_NAME = re.compile(r'[a-z][a-z0-9_]*\Z')
_IDENTIFIER = re.compile(r'[A-Za-z_][A-Za-z0-9_]*\Z')
_DEPENDENCY = re.compile(r'[A-Za-z0-9][A-Za-z0-9_.+-]*\Z')


class CreateError(Ros2liteError):
    """The package cannot be created as asked; the message says why."""


@dataclass(frozen=True)
class Created:
    """What was made: the package directory and whether its license was one we know."""

    directory: Path
    license_file: bool


def default_maintainer(name: str | None = None) -> tuple[str, str]:
    """(name, email) as ros2 pkg create guesses them: `name` or the login name, and git's
    `user.email`, else `<name>@todo.todo`."""
    name = name or getpass.getuser()
    email = ''
    git = shutil.which('git')
    if git is not None:
        try:
            done = subprocess.run(
                [git, 'config', 'user.email'],
                capture_output=True,
                text=True,
                timeout=5,
                check=False,
            )
            email = done.stdout.strip()
        except (OSError, subprocess.SubprocessError):
            email = ''
    return name, email or f'{name}@todo.todo'


def prepare_spec(spec: PackageSpec) -> tuple[PackageSpec, list[str]]:
    """Check every name and fill in what the build type implies; returns the spec to create
    and warnings for the user. Raises :class:`CreateError`."""
    if spec.build_type not in BUILD_TYPES:
        raise CreateError(
            f"invalid build type '{spec.build_type}' (choose from {', '.join(BUILD_TYPES)})"
        )
    if not _PACKAGE_NAME.match(spec.name):
        raise CreateError(
            f"Aborted since '{spec.name}' is not a valid package name: use lowercase letters, "
            'digits and underscores, starting with a letter (REP 144).'
        )
    if spec.build_type == 'ament_python' and spec.name == 'test':
        raise CreateError(
            "Aborted since 'ament_python' packages can't be named 'test'. "
            'Please choose a different package name.'
        )
    for label, value in (('node', spec.node_name), ('library', spec.library_name)):
        if value is not None and not _IDENTIFIER.match(value):
            raise CreateError(
                f"invalid {label} name '{value}': use letters, digits and underscores, "
                'not starting with a digit'
            )
    for dep in spec.dependencies:
        if not _DEPENDENCY.match(dep):
            raise CreateError(f"invalid dependency name '{dep}'")
    if spec.package_format not in (2, 3):
        raise CreateError(f'invalid package format {spec.package_format} (choose 2 or 3)')
    warnings: list[str] = []
    node = spec.node_name
    if node is not None and node == spec.library_name:
        node = f'{node}_node'
        warnings += [
            '[WARNING] node name can not be equal to the library name',
            f'[WARNING] renaming node to {node}',
        ]
    buildtool: tuple[str, ...] = ()
    tests: tuple[str, ...] = ()
    if spec.build_type == 'ament_cmake':
        buildtool = ('ament_cmake_ros',) if spec.library_name else ('ament_cmake',)
        tests = ('ament_lint_auto', 'ament_lint_common')
    elif spec.build_type == 'ament_python':
        tests = ('ament_copyright', 'ament_flake8', 'ament_pep257', 'python3-pytest')
    prepared = replace(
        spec, node_name=node, buildtool_dependencies=buildtool, test_dependencies=tests
    )
    return prepared, warnings


class _Writer:
    """Creates folders and files under a fresh package directory, reporting each step."""

    def __init__(self, report: Callable[[str], None]) -> None:
        self.report = report

    def folder(self, path: str) -> str:
        self.report(f'creating folder {path}')
        os.makedirs(path, exist_ok=True)
        return path

    def file(self, path: str, content: str, *, quiet: bool = False) -> None:
        if not quiet:
            self.report(f'creating {path}')

        with os.fdopen(create_new(path), 'w', encoding='utf-8') as out:
            out.write(content)


def create_package(spec: PackageSpec, destination: str, report: Callable[[str], None]) -> Created:
    """Write the package `spec` (already through :func:`prepare_spec`) into
    `destination/<name>`, calling `report` with each of ros2 pkg create's progress lines.
    Raises :class:`CreateError` when the directory exists or cannot be made."""
    package_dir = os.path.join(destination, spec.name)
    if os.path.lexists(package_dir):
        raise CreateError(
            f'\nAborted!\nThe directory already exists: {package_dir}\n'
            'Either remove the directory or choose a different destination directory or '
            'package name'
        )
    w = _Writer(report)
    try:
        os.makedirs(destination, exist_ok=True)
        report(f'creating folder {package_dir}')
        os.mkdir(package_dir)
        w.file(os.path.join(package_dir, 'package.xml'), templates.package_xml(spec))
        if spec.build_type == 'ament_python':
            _populate_python(spec, package_dir, w)
        else:
            _populate_cmake(spec, package_dir, w)
        license_files = _LICENSE_TEXTS.get(spec.license)
        if license_files:
            text = ''.join((_LICENSE_DIR / f).read_text(encoding='utf-8') for f in license_files)
            w.file(os.path.join(package_dir, 'LICENSE'), text, quiet=True)
    except OSError as e:
        raise CreateError(f'unable to create {e.filename or package_dir}: {e.strerror}') from None
    return Created(Path(package_dir), license_files is not None)


def _populate_python(spec: PackageSpec, package_dir: str, w: _Writer) -> None:
    w.report('creating source folder')
    source = w.folder(os.path.join(package_dir, spec.name))
    w.file(os.path.join(package_dir, 'setup.py'), templates.setup_py(spec))
    w.file(os.path.join(package_dir, 'setup.cfg'), templates.setup_cfg(spec))
    resource = w.folder(os.path.join(package_dir, 'resource'))
    w.file(os.path.join(resource, spec.name), '')
    w.file(os.path.join(source, '__init__.py'), '')
    tests = w.folder(os.path.join(package_dir, 'test'))
    w.file(os.path.join(tests, 'test_copyright.py'), templates.test_copyright())
    w.file(os.path.join(tests, 'test_flake8.py'), templates.test_flake8())
    w.file(os.path.join(tests, 'test_pep257.py'), templates.test_pep257())
    if spec.node_name:
        w.file(os.path.join(source, f'{spec.node_name}.py'), templates.python_node(spec))


def _populate_cmake(spec: PackageSpec, package_dir: str, w: _Writer) -> None:
    w.report('creating source and include folder')
    source = w.folder(os.path.join(package_dir, 'src'))
    include = w.folder(os.path.join(package_dir, 'include', spec.name))
    if spec.build_type == 'cmake':
        w.file(os.path.join(package_dir, 'CMakeLists.txt'), templates.cmake_lists(spec))
        w.file(
            os.path.join(package_dir, f'{spec.name}Config.cmake.in'),
            templates.cmake_config_in(spec),
        )
        w.file(
            os.path.join(package_dir, f'{spec.name}ConfigVersion.cmake.in'),
            templates.cmake_config_version_in(spec),
        )
    else:
        w.file(os.path.join(package_dir, 'CMakeLists.txt'), templates.ament_cmake_lists(spec))
    if spec.node_name:
        w.file(os.path.join(source, f'{spec.node_name}.cpp'), templates.cpp_node(spec))
    if spec.library_name:
        lib = spec.library_name
        w.file(os.path.join(include, f'{lib}.hpp'), templates.cpp_header(spec))
        w.file(os.path.join(source, f'{lib}.cpp'), templates.cpp_library(spec))
        w.file(os.path.join(include, 'visibility_control.h'), templates.visibility_control(spec))
