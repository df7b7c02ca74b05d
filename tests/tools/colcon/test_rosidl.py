"""Checking an interface package's files as rosidl would: each problem one line with file and
line; what a ROS install holds, listed for the installer."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite.tools.colcon.cmake import read_cmake_package
from ros2lite.tools.colcon.rosidl import (
    InterfacePackageError,
    check_interfaces,
    install_plan,
    resource_index_entry,
)


def _package(tmp_path: Path, files: dict[str, str], deps: str = 'builtin_interfaces') -> Path:
    listed = ' '.join(f'"{name}"' for name in files)
    (tmp_path / 'CMakeLists.txt').write_text(
        'project(custom_interfaces)\n'
        f'rosidl_generate_interfaces(${{PROJECT_NAME}} {listed} DEPENDENCIES {deps})\n'
    )
    for name, text in files.items():
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text(text)
    return tmp_path


def _check(path: Path, provides: set[str] = frozenset({'builtin_interfaces/msg/Time'})) -> list:
    cmake = read_cmake_package(path, 'custom_interfaces')
    return check_interfaces(path, 'custom_interfaces', cmake, provides.__contains__)


def test_good_files_are_listed_for_install(tmp_path: Path) -> None:
    path = _package(
        tmp_path,
        {
            'msg/Age.msg': 'int64 age\nbuiltin_interfaces/Time stamp\n',
            'msg/Person.msg': 'Age age\nstring name\n',
            'srv/Ask.srv': 'string q\n---\nAge a\n',
            'action/Count.action': 'int32 n\n---\nint32 total\n---\nint32 done\n',
        },
    )
    files = _check(path)
    assert [(f.relative, f.kind, f.name) for f in files] == [
        ('msg/Age.msg', 'msg', 'custom_interfaces/msg/Age'),
        ('msg/Person.msg', 'msg', 'custom_interfaces/msg/Person'),
        ('srv/Ask.srv', 'srv', 'custom_interfaces/srv/Ask'),
        ('action/Count.action', 'action', 'custom_interfaces/action/Count'),
    ]
    assert install_plan('custom_interfaces', files)[-1] == (
        'package.xml',
        'share/custom_interfaces/package.xml',
    )
    assert install_plan('custom_interfaces', files)[0] == (
        'msg/Age.msg',
        'share/custom_interfaces/msg/Age.msg',
    )
    assert resource_index_entry(files) == (
        'msg/Age.msg\nmsg/Person.msg\nsrv/Ask.srv\naction/Count.action\n'
    )


@pytest.mark.parametrize(
    ('files', 'message'),
    [
        ({'msg/Age.msg': 'int64 age\nfloat99 w\n'}, "msg/Age.msg:2: invalid type name 'float99'"),
        ({'msg/Age.msg': 'int64 age\nint64 age\n'}, "msg/Age.msg:2: duplicate name 'age'"),
        ({'srv/Ask.srv': 'string q\n'}, "srv/Ask.srv: expected 1 '---' separator(s), found 0"),
        (
            {'msg/Age.msg': '# years\nMissing m\n'},
            'msg/Age.msg:2: custom_interfaces/msg/Missing is not among the files',
        ),
        (
            {'msg/Age.msg': 'geometry_msgs/Point p\n'},
            "msg/Age.msg:1: geometry_msgs/msg/Point comes from package 'geometry_msgs', which "
            'rosidl_generate_interfaces does not list in DEPENDENCIES',
        ),
        (
            {'msg/Age.msg': 'builtin_interfaces/Nope n\n'},
            'msg/Age.msg:1: no package provides builtin_interfaces/msg/Nope',
        ),
        ({'msg/age.msg': 'int64 a\n'}, 'must be CamelCase'),
        ({'srv/Age.msg': 'int64 a\n'}, "a .msg file belongs in the package's msg/ folder"),
        ({'msg/Age.idl': 'module x {};\n'}, 'not .idl'),
    ],
)
def test_each_problem_is_one_line_naming_the_file(
    tmp_path: Path, files: dict[str, str], message: str
) -> None:
    with pytest.raises(InterfacePackageError) as e:
        _check(_package(tmp_path, files))
    assert message in str(e.value)
    assert '\n' not in str(e.value)


def test_a_listed_file_that_is_missing_is_named_with_the_call(tmp_path: Path) -> None:
    path = _package(tmp_path, {})
    (path / 'CMakeLists.txt').write_text(
        'project(custom_interfaces)\nrosidl_generate_interfaces(${PROJECT_NAME} "msg/Age.msg")\n'
    )
    with pytest.raises(InterfacePackageError, match=r'CMakeLists.txt:2: msg/Age.msg does not'):
        _check(path)
