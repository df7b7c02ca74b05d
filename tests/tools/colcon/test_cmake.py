"""Reading a CMakeLists.txt without CMake: the interface files, the DEPENDENCIES, and what
needs a real build, with file and line for what cannot be read."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite.tools.colcon.cmake import (
    CMakeError,
    file_install_plan,
    mentions_rosidl,
    parse_calls,
    read_cmake_package,
)

COURSE = """cmake_minimum_required(VERSION 3.8)
project(custom_interfaces)

if(CMAKE_COMPILER_IS_GNUCXX OR CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  add_compile_options(-Wall -Wextra -Wpedantic)
endif()

find_package(ament_cmake REQUIRED)
find_package(rosidl_default_generators REQUIRED)
set(msg_files "msg/Age.msg" msg/Person.msg)
rosidl_generate_interfaces(${PROJECT_NAME}
  ${msg_files}
  "srv/AddTwo.srv"  # a comment
  "${CMAKE_CURRENT_SOURCE_DIR}/action/Count.action"
  DEPENDENCIES builtin_interfaces geometry_msgs
)
#[[ a bracket
comment ]]
ament_package()
"""


def _write(tmp_path: Path, text: str) -> Path:
    (tmp_path / 'CMakeLists.txt').write_text(text)
    return tmp_path


def test_the_course_interface_package(tmp_path: Path) -> None:
    found = read_cmake_package(_write(tmp_path, COURSE), 'custom_interfaces')
    assert found.interfaces == [
        'msg/Age.msg',
        'msg/Person.msg',
        'srv/AddTwo.srv',
        'action/Count.action',
    ]
    assert found.dependencies == ['builtin_interfaces', 'geometry_msgs']
    assert (found.has_interfaces, found.rosidl_line, found.unbuilt) == (True, 11, [])


def test_cpp_targets_are_named_with_their_lines(tmp_path: Path) -> None:
    text = COURSE.replace(
        'ament_package()',
        'add_executable(talker src/talker.cpp)\ninstall(TARGETS talker DESTINATION lib)\n'
        'ament_package()',
    )
    found = read_cmake_package(_write(tmp_path, text), 'custom_interfaces')
    assert found.unbuilt_summary() == 'add_executable (line 19), install (line 20)'


def test_an_empty_cpp_package_has_nothing_ros2lite_builds(tmp_path: Path) -> None:
    found = read_cmake_package(
        _write(
            tmp_path, 'project(my_package)\nfind_package(ament_cmake REQUIRED)\nament_package()\n'
        ),
        'my_package',
    )
    assert (found.has_interfaces, found.unbuilt) == (False, [])


@pytest.mark.parametrize(
    ('text', 'message'),
    [
        ('project(p\n', "CMakeLists.txt:1: project( is never closed with ')'"),
        ('project(p)\n)\n', "CMakeLists.txt:2: expected a command, found ')'"),
        (
            'rosidl_generate_interfaces(${NOPE} "msg/A.msg")\n',
            'CMakeLists.txt:1: ${NOPE} is not set',
        ),
        ('project(p)\nrosidl_generate_interfaces(${PROJECT_NAME})\n', 'CMakeLists.txt:2: '),
        ('project(p)\nrosidl_generate_interfaces(p "../x/msg/A.msg")\n', 'leaves the package'),
        ('project(p)\nrosidl_generate_interfaces(p "/etc/msg/A.msg")\n', 'outside the package'),
    ],
)
def test_what_cannot_be_read_is_one_line_with_file_and_line(
    tmp_path: Path, text: str, message: str
) -> None:
    with pytest.raises(CMakeError) as e:
        read_cmake_package(_write(tmp_path, text), 'p')
    assert message in str(e.value)
    assert '\n' not in str(e.value)


def test_a_missing_file_is_named(tmp_path: Path) -> None:
    with pytest.raises(CMakeError, match=r'CMakeLists\.txt: cannot be read'):
        read_cmake_package(tmp_path, 'p')


def test_calls_keep_their_first_line() -> None:
    calls = parse_calls('a(x\n  y)\n\nB("q\nr")\n')
    assert [(c.name, c.args, c.line) for c in calls] == [
        ('a', ('x', 'y'), 1),
        ('b', ('"q\nr"',), 4),
    ]


def test_list_append_adds_interface_files(tmp_path: Path) -> None:
    text = (
        'project(p)\nset(files msg/A.msg)\nlist(APPEND files "msg/B.msg" ${PROJECT_NAME})\n'
        'rosidl_generate_interfaces(p ${files})\n'
    )
    found = read_cmake_package(_write(tmp_path, text), 'p')
    assert found.interfaces == ['msg/A.msg', 'msg/B.msg', 'p']


def test_an_unreadable_file_is_an_interface_package_only_if_it_says_so(tmp_path: Path) -> None:
    _write(tmp_path, 'project(p\nadd_executable(x x.cpp)\n')
    assert not mentions_rosidl(tmp_path)
    _write(tmp_path, 'project(p\n  rosidl_generate_interfaces (p "msg/A.msg")\n')
    assert mentions_rosidl(tmp_path)


def test_install_calls_ros2lite_copies_and_those_it_leaves(tmp_path: Path) -> None:
    for name in ('launch/a.launch.py', 'launch/sub/b.yaml', 'config/p.yaml', 'scripts/go.py'):
        (tmp_path / name).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / name).write_text('')
    text = (
        'project(b)\n'
        'install(DIRECTORY launch config/ DESTINATION share/${PROJECT_NAME})\n'
        'install(PROGRAMS scripts/go.py DESTINATION lib/${PROJECT_NAME})\n'
        'install(TARGETS x DESTINATION lib/${PROJECT_NAME})\n'
        'install(DIRECTORY launch DESTINATION share/b FILES_MATCHING PATTERN *.py)\n'
        'install(FILES /etc/passwd DESTINATION share/b)\n'
    )
    found = read_cmake_package(_write(tmp_path, text), 'b')
    assert found.unbuilt_summary() == 'install (line 4), install (line 5), install (line 6)'
    assert file_install_plan(tmp_path, found.installs) == [
        ('launch/a.launch.py', 'share/b/launch/a.launch.py', False),
        ('launch/sub/b.yaml', 'share/b/launch/sub/b.yaml', False),
        ('config/p.yaml', 'share/b/p.yaml', False),
        ('scripts/go.py', 'lib/b/go.py', True),
    ]
    (tmp_path / 'scripts' / 'go.py').unlink()
    with pytest.raises(
        CMakeError, match=r'CMakeLists\.txt:3: install\(PROGRAMS\) names scripts/go'
    ):
        file_install_plan(tmp_path, found.installs)
