"""`pkg create`: the trees and files of each build type, and what is refused."""

from __future__ import annotations

import ast
import os
from pathlib import Path

import pytest

from ros2lite.pkg.create import CreateError, PackageSpec, create_package, prepare_spec
from ros2lite.pkg.manifest import read_manifest
from ros2lite.pkg.setup_files import read_python_package


def _create(tmp_path: Path, **kw: object) -> tuple[Path, list[str]]:
    spec, _warnings = prepare_spec(PackageSpec(**kw))  # type: ignore[arg-type]
    lines: list[str] = []
    created = create_package(spec, str(tmp_path), lines.append)
    return created.directory, lines


def _tree(root: Path) -> list[str]:
    return sorted(str(p.relative_to(root)) for p in root.rglob('*') if p.is_file())


def test_ament_python(tmp_path: Path) -> None:
    pkg, lines = _create(
        tmp_path,
        name='py_pubsub',
        build_type='ament_python',
        license='Apache-2.0',
        dependencies=('rclpy', 'std_msgs'),
        node_name='talker',
        maintainer_name="O'Brien <x>",
        maintainer_email='ob@example.com',
        description='A "quoted" & <tagged> description',
    )
    assert _tree(pkg) == [
        'LICENSE',
        'package.xml',
        'py_pubsub/__init__.py',
        'py_pubsub/talker.py',
        'resource/py_pubsub',
        'setup.cfg',
        'setup.py',
        'test/test_copyright.py',
        'test/test_flake8.py',
        'test/test_pep257.py',
    ]
    d = str(tmp_path)
    assert lines == [
        f'creating folder {d}/py_pubsub',
        f'creating {d}/py_pubsub/package.xml',
        'creating source folder',
        f'creating folder {d}/py_pubsub/py_pubsub',
        f'creating {d}/py_pubsub/setup.py',
        f'creating {d}/py_pubsub/setup.cfg',
        f'creating folder {d}/py_pubsub/resource',
        f'creating {d}/py_pubsub/resource/py_pubsub',
        f'creating {d}/py_pubsub/py_pubsub/__init__.py',
        f'creating folder {d}/py_pubsub/test',
        f'creating {d}/py_pubsub/test/test_copyright.py',
        f'creating {d}/py_pubsub/test/test_flake8.py',
        f'creating {d}/py_pubsub/test/test_pep257.py',
        f'creating {d}/py_pubsub/py_pubsub/talker.py',
    ]
    m = read_manifest(pkg / 'package.xml')
    assert (m.name, m.format, m.build_type, m.version) == ('py_pubsub', 3, 'ament_python', '0.0.0')
    assert m.description == 'A "quoted" & <tagged> description'
    assert m.maintainers == (("O'Brien <x>", 'ob@example.com'),)
    assert m.depends['depend'] == ('rclpy', 'std_msgs')
    assert m.depends['test_depend'] == (
        'ament_copyright',
        'ament_flake8',
        'ament_pep257',
        'python3-pytest',
    )
    assert 'package_format3.xsd' in (pkg / 'package.xml').read_text()
    # setup.py is valid Python holding the odd strings safely, and declares the node
    setup = (pkg / 'setup.py').read_text()
    ast.parse(setup)
    assert "maintainer='O\\'Brien <x>'" in setup or 'maintainer="O\'Brien <x>"' in setup
    assert read_python_package(pkg).console_scripts == {'talker': 'py_pubsub.talker:main'}
    assert (pkg / 'setup.cfg').read_text() == (
        '[develop]\nscript_dir=$base/lib/py_pubsub\n[install]\ninstall_scripts=$base/lib/py_pubsub\n'
    )
    assert (pkg / 'resource' / 'py_pubsub').read_text() == ''
    assert 'Apache License' in (pkg / 'LICENSE').read_text()
    for test in (pkg / 'test').iterdir():
        ast.parse(test.read_text())


def test_ament_cmake_with_node_and_library(tmp_path: Path) -> None:
    pkg, lines = _create(
        tmp_path,
        name='my_pkg',
        dependencies=('rclcpp',),
        node_name='my_node',
        library_name='my_lib',
    )
    assert _tree(pkg) == [
        'CMakeLists.txt',
        'include/my_pkg/my_lib.hpp',
        'include/my_pkg/visibility_control.h',
        'package.xml',
        'src/my_lib.cpp',
        'src/my_node.cpp',
    ]
    assert lines[2:5] == [
        'creating source and include folder',
        f'creating folder {tmp_path}/my_pkg/src',
        f'creating folder {tmp_path}/my_pkg/include/my_pkg',
    ]
    cmake = (pkg / 'CMakeLists.txt').read_text()
    assert 'project(my_pkg)' in cmake and 'find_package(rclcpp REQUIRED)' in cmake
    assert 'add_executable(my_node src/my_node.cpp)' in cmake and 'ament_package()' in cmake
    assert 'find_package(ament_cmake_ros REQUIRED)' in cmake
    m = read_manifest(pkg / 'package.xml')
    assert m.depends['buildtool_depend'] == ('ament_cmake_ros',)
    assert m.depends['test_depend'] == ('ament_lint_auto', 'ament_lint_common')
    assert 'class MyLib' in (pkg / 'include' / 'my_pkg' / 'my_lib.hpp').read_text()
    assert not (pkg / 'LICENSE').exists()


def test_cmake_package_config_files(tmp_path: Path) -> None:
    pkg, _ = _create(tmp_path, name='plain', build_type='cmake', license='MIT')
    assert _tree(pkg) == [
        'CMakeLists.txt',
        'LICENSE',
        'package.xml',
        'plainConfig.cmake.in',
        'plainConfigVersion.cmake.in',
    ]
    assert 'Permission is hereby granted' in (pkg / 'LICENSE').read_text()


def test_node_named_like_the_library_is_renamed() -> None:
    spec, warnings = prepare_spec(PackageSpec(name='p', node_name='x', library_name='x'))
    assert spec.node_name == 'x_node'
    assert warnings == [
        '[WARNING] node name can not be equal to the library name',
        '[WARNING] renaming node to x_node',
    ]


@pytest.mark.parametrize(
    ('spec', 'message'),
    [
        (PackageSpec(name='../evil'), "'../evil' is not a valid package name"),
        (PackageSpec(name='Caps'), "'Caps' is not a valid package name"),
        (PackageSpec(name='test', build_type='ament_python'), "can't be named 'test'"),
        (PackageSpec(name='p', node_name='a b'), "invalid node name 'a b'"),
        (PackageSpec(name='p', dependencies=('x;y',)), "invalid dependency name 'x;y'"),
        (PackageSpec(name='p', build_type='meson'), "invalid build type 'meson'"),
    ],
)
def test_refused(spec: PackageSpec, message: str) -> None:
    with pytest.raises(CreateError, match=message.replace('.', r'\.')):
        prepare_spec(spec)


def test_existing_directory_or_symlink_is_never_written(tmp_path: Path) -> None:
    target = tmp_path / 'elsewhere'
    target.mkdir()
    os.symlink(target, tmp_path / 'taken')
    spec, _ = prepare_spec(PackageSpec(name='taken'))
    with pytest.raises(CreateError, match='The directory already exists'):
        create_package(spec, str(tmp_path), lambda _line: None)
    assert list(target.iterdir()) == []
