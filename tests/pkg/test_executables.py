"""The executable index: bundled demos, Python entry points and ament prefixes, and which of
them owns a package."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from ros2lite.pkg.executables import (
    ENTRY_POINT_GROUP,
    MultipleExecutablesError,
    PackageNotFoundError,
    find_executable,
    get_executables,
    list_packages,
)


@pytest.fixture(autouse=True)
def no_ament(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv('AMENT_PREFIX_PATH', raising=False)


def make_ament_prefix(root: Path, package: str, files: dict[str, str]) -> Path:
    """A minimal install prefix: the ament index marker plus files under lib/<package>."""
    index = root / 'share' / 'ament_index' / 'resource_index' / 'packages'
    index.mkdir(parents=True, exist_ok=True)
    (index / package).write_text('')
    for rel, body in files.items():
        path = root / 'lib' / package / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(body)
        path.chmod(0o755 if body.startswith('#!') else 0o644)
    return root


def make_entry_points(root: Path, entries: dict[str, str]) -> Path:
    """A fake installed distribution declaring `ros2lite.executables` entry points."""
    dist = root / 'fake_nodes-1.0.dist-info'
    dist.mkdir(parents=True)
    (dist / 'METADATA').write_text('Metadata-Version: 2.1\nName: fake-nodes\nVersion: 1.0\n')
    lines = [f'[{ENTRY_POINT_GROUP}]'] + [f'{k} = {v}' for k, v in entries.items()]
    (dist / 'entry_points.txt').write_text('\n'.join(lines) + '\n')
    return root


def test_bundled_demos() -> None:
    exes = get_executables('demo_nodes_py')
    assert [e.name for e in exes] == [
        'add_two_ints_client',
        'add_two_ints_client_async',
        'add_two_ints_server',
        'async_param_client',
        'introspection',
        'listener',
        'listener_qos',
        'listener_serialized',
        'matched_event_detect',
        'set_parameters_callback',
        'talker',
        'talker_qos',
        'use_logger_service',
    ]
    talker = find_executable('demo_nodes_py', 'talker')
    assert talker is not None and talker.origin == 'bundled' and talker.is_python
    assert find_executable('demo_nodes_py', 'nope') is None
    assert 'demo_nodes_py' in list_packages()
    with pytest.raises(PackageNotFoundError, match="Package 'no_such_pkg' not found"):
        get_executables('no_such_pkg')


def test_python_command_runs_like_a_console_script(tmp_path: Path) -> None:
    (tmp_path / 'shadow_mod.py').write_text(
        'import sys\ndef main():\n    print(sys.argv)\n    return 3\n'
    )
    from ros2lite.pkg.executables import PackageExecutable

    exe = PackageExecutable('pkg', 'shown_name', 'shadow_mod:main', 'entry point')
    cmd = exe.command(['--ros-args', '-r', 'a:=b'])
    proc = subprocess.run(
        cmd,
        capture_output=True,
        text=True,
        timeout=30,
        env={**os.environ, 'PYTHONPATH': str(tmp_path)},
    )
    assert proc.returncode == 3
    assert proc.stdout.strip() == "['shown_name', '--ros-args', '-r', 'a:=b']"
    # the working directory is not importable (as with console scripts)
    (tmp_path / 'cwd_only.py').write_text('def main():\n    return 0\n')
    missing = PackageExecutable('pkg', 'x', 'cwd_only:main', 'entry point')
    proc = subprocess.run(
        missing.command(), capture_output=True, text=True, timeout=30, cwd=tmp_path
    )
    assert proc.returncode == 1 and 'ModuleNotFoundError' in proc.stderr


def test_ament_prefix(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    first = make_ament_prefix(
        tmp_path / 'ws',
        'my_pkg',
        {
            'node': '#!/bin/sh\n',
            'sub/tool': '#!/bin/sh\n',
            'data.txt': 'not executable',
            '.hidden/node2': '#!/bin/sh\n',
        },
    )
    second = make_ament_prefix(tmp_path / 'opt', 'my_pkg', {'other': '#!/bin/sh\n'})
    make_ament_prefix(tmp_path / 'opt', 'demo_nodes_py', {'talker': '#!/bin/sh\n'})
    monkeypatch.setenv('AMENT_PREFIX_PATH', f'{first}{os.pathsep}{second}')
    exes = get_executables('my_pkg')  # the first prefix owns the package
    assert sorted(e.name for e in exes) == ['node', 'tool']
    node = find_executable('my_pkg', 'node')
    assert node is not None and node.origin == 'ament' and not node.is_python
    assert node.command(['a']) == [str(first / 'lib' / 'my_pkg' / 'node'), 'a']
    # an ament package shadows a bundled one of the same name
    talker = find_executable('demo_nodes_py', 'talker')
    assert talker is not None and talker.origin == 'ament'
    assert {'my_pkg', 'demo_nodes_py'} <= set(list_packages())


def test_multiple_executables(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    prefix = make_ament_prefix(tmp_path, 'dup', {'a/run': '#!/bin/sh\n', 'b/run': '#!/bin/sh\n'})
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(prefix))
    with pytest.raises(MultipleExecutablesError) as info:
        find_executable('dup', 'run')
    assert str(info.value) == (
        f'Multiple executables found:\n- {prefix}/lib/dup/a/run\n- {prefix}/lib/dup/b/run'
    )


def test_entry_points(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    make_entry_points(
        tmp_path,
        {
            'ep_pkg.hello': 'hello_mod:main',
            'ep_pkg.deep.name': 'hello_mod:Obj.run',
            'demo_nodes_py.talker': 'hello_mod:main',
            'no_dot_name': 'hello_mod:main',
        },
    )
    monkeypatch.syspath_prepend(str(tmp_path))
    hello = find_executable('ep_pkg', 'hello')
    assert hello is not None and hello.origin == 'entry point'
    assert hello.target == 'hello_mod:main'
    deep = find_executable('ep_pkg', 'deep.name')
    assert deep is not None and deep.target == 'hello_mod:Obj.run'
    # an entry-point package owns that package name entirely
    assert [e.name for e in get_executables('demo_nodes_py')] == ['talker']
    assert find_executable('demo_nodes_py', 'listener') is None
    assert 'ep_pkg' in list_packages() and 'no_dot_name' not in list_packages()
    assert sys.path[0] == str(tmp_path)


def test_workspace_python_package_runs_from_its_sources(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from ros2lite.pkg.environment import child_environment
    from ros2lite.pkg.index import PackageIndex
    from tests.pkg.workspaces import write_package

    ws = tmp_path / 'ws'
    write_package(
        ws / 'src' / 'py_tools',
        'py_tools',
        scripts={'hello': 'py_tools.hello:main'},
        modules={
            'py_tools/__init__.py': '',
            'py_tools/hello.py': (
                'import sys\ndef main():\n    print("hi", sys.argv)\n    return 4\n'
            ),
        },
    )
    write_package(ws / 'src' / 'cpp_thing', 'cpp_thing', build_type='ament_cmake')
    monkeypatch.chdir(tmp_path)  # outside the workspace: found through the variable
    monkeypatch.setenv('ROS2LITE_WORKSPACE', str(ws))
    index = PackageIndex()
    hello = find_executable('py_tools', 'hello', index=index)
    assert hello is not None and hello.origin == 'workspace'
    assert hello.pythonpath == (str(ws / 'src' / 'py_tools'),)
    assert hello.path() == str(ws / 'src' / 'py_tools' / 'py_tools' / 'hello.py')
    assert get_executables('cpp_thing', index=index) == []  # C++ needs a build first
    env = child_environment(pythonpath=hello.pythonpath, workspaces=index.workspaces())
    proc = subprocess.run(
        hello.command(['--ros-args']), capture_output=True, text=True, timeout=60, env=env
    )
    assert (proc.returncode, proc.stdout) == (4, "hi ['hello', '--ros-args']\n")


def test_cpp_demo_names_run_the_python_twins() -> None:
    from ros2lite.pkg.executables import ExecutableNotFoundError, resolve_executable

    resolved = resolve_executable('demo_nodes_cpp', 'add_two_ints_server')
    assert resolved.executable.package == 'demo_nodes_py'
    assert resolved.executable.name == 'add_two_ints_server'
    assert resolved.note == (
        'demo_nodes_cpp (C++) is not installed; running demo_nodes_py add_two_ints_server, '
        'its Python equivalent'
    )
    assert resolve_executable('demo_nodes_py', 'talker').note is None
    # demo_nodes_cpp's own executables (Jazzy's demo_nodes_py has none of these) run too,
    # and only under the C++ package's name
    board = resolve_executable('demo_nodes_cpp', 'parameter_blackboard')
    assert board.executable.target == 'ros2lite.bundled.demo_nodes_py.parameter_blackboard:main'
    assert board.note == (
        'demo_nodes_cpp (C++) is not installed; running a Python parameter_blackboard bundled '
        'with ros2lite'
    )
    with pytest.raises(ExecutableNotFoundError):
        resolve_executable('demo_nodes_py', 'parameter_blackboard')


def test_cpp_demo_installed_is_used_as_is(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from ros2lite.pkg.executables import resolve_executable

    prefix = make_ament_prefix(tmp_path, 'demo_nodes_cpp', {'talker': '#!/bin/sh\n'})
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(prefix))
    resolved = resolve_executable('demo_nodes_cpp', 'talker')
    assert resolved.note is None and resolved.executable.origin == 'ament'


def test_close_matches_in_errors() -> None:
    from ros2lite.pkg.executables import ExecutableNotFoundError, resolve_executable

    with pytest.raises(PackageNotFoundError, match=r"not found; did you mean: demo_nodes_py\?"):
        resolve_executable('demo_node_py', 'talker')
    with pytest.raises(ExecutableNotFoundError, match=r'^No executable found; did you mean: '):
        resolve_executable('demo_nodes_py', 'talkr')
    with pytest.raises(ExecutableNotFoundError, match=r'^No executable found$'):
        resolve_executable('demo_nodes_py', 'zzzzzz')
