"""`interface show` with the official Jazzy interface wheels installed in the environment:
found with no variable set, they win over the bundled copies and bring their comments.

The wheels are installed with pip (from PyPI, a few seconds) into a throw-away environment
that sees this ros2lite, so the test controls what is installed where. The expected output is
made from the installed `.msg` files themselves: the top-level type verbatim, nested types
verbatim with `--all-comments`, and without comment and blank lines otherwise.
"""

from __future__ import annotations

import os
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

# Jazzy's releases; the exact versions keep the run reproducible
WHEELS = ('ros-std-msgs==5.3.6', 'ros-geometry-msgs==5.3.6', 'ros-builtin-interfaces==2.0.3')


@pytest.fixture(scope='module')
def environment(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A venv whose own prefix holds the wheels and which imports this ros2lite."""
    root = tmp_path_factory.mktemp('wheels-env')
    subprocess.run([sys.executable, '-m', 'venv', '--without-pip', str(root)], check=True)
    where = 'import sysconfig; print(sysconfig.get_path("purelib"))'
    purelib = subprocess.run(
        [str(root / 'bin' / 'python'), '-c', where],
        capture_output=True,
        text=True,
        check=True,
    ).stdout.strip()
    ours = [sysconfig.get_path('purelib'), *(p for p in sys.path if p and os.path.isdir(p))]
    (Path(purelib) / 'parent.pth').write_text(
        'import site; ' + '; '.join(f'site.addsitedir({p!r})' for p in dict.fromkeys(ours)) + '\n'
    )
    subprocess.run(
        [sys.executable, '-m', 'pip', 'install', '-q', '--no-deps', '--only-binary=:all:',
         '--no-compile', '--disable-pip-version-check', '--prefix', str(root), *WHEELS],
        check=True,
        timeout=300,
    )  # fmt: skip
    return root


def show(env: Path, *args: str) -> str:
    proc = subprocess.run(
        [str(env / 'bin' / 'python'), '-m', 'ros2lite', 'interface', 'show', *args],
        capture_output=True,
        text=True,
        timeout=60,
        env={k: v for k, v in os.environ.items() if k not in ('AMENT_PREFIX_PATH', 'PYTHONPATH')}
        | {'ROS2LITE_INTERFACE_PATH': ''},
    )
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def lines(env: Path, package: str, name: str) -> list[str]:
    text = (env / 'share' / package / 'msg' / f'{name}.msg').read_text()
    return [line.rstrip() for line in text.splitlines()]


def bare(raw: list[str]) -> list[str]:
    """The lines left without comments (these files have no trailing comments)."""
    return [line for line in raw if line and not line.startswith('#')]


def tabbed(raw: list[str]) -> list[str]:
    return ['\t' + line if line else '' for line in raw]


CASES = {
    # type: (package, file), the nested field line → its (package, file)
    'std_msgs/msg/Header': (
        ('std_msgs', 'Header'),
        {'builtin_interfaces/Time stamp': ('builtin_interfaces', 'Time')},
    ),
    'geometry_msgs/msg/Twist': (
        ('geometry_msgs', 'Twist'),
        {
            'Vector3  linear': ('geometry_msgs', 'Vector3'),
            'Vector3  angular': ('geometry_msgs', 'Vector3'),
        },
    ),
}


def expected(env: Path, type_name: str, mode: str) -> str:
    (package, name), nested = CASES[type_name]
    top = lines(env, package, name)
    out: list[str] = []
    for line in top if mode != '--no-comments' else bare(top):
        out.append(line)
        if line in nested:
            inner = lines(env, *nested[line])
            out += tabbed(inner if mode == '--all-comments' else bare(inner))
    return ''.join(line + '\n' for line in out)


@pytest.mark.parametrize('type_name', sorted(CASES))
def test_installed_interfaces_show_their_comments(environment: Path, type_name: str) -> None:
    package, name = CASES[type_name][0]
    assert any(line.startswith('#') for line in lines(environment, package, name))
    for mode in ('', '--no-comments', '--all-comments'):
        assert show(environment, *filter(None, [mode]), type_name) == expected(
            environment, type_name, mode
        ), mode


def test_installed_definitions_keep_the_type_hashes(environment: Path) -> None:
    proc = subprocess.run(
        [str(environment / 'bin' / 'python'), '-c',
         'import json, sys\n'
         'from ros2lite.interfaces import type_hash\n'
         'from ros2lite.pkg.index import PackageIndex\n'
         'names = ["std_msgs/msg/Header", "geometry_msgs/msg/TwistStamped"]\n'
         'origins = [PackageIndex().find(n.split("/")[0]).origin for n in names]\n'
         'print(json.dumps([origins, [type_hash(n) for n in names]]))'],
        capture_output=True,
        text=True,
        timeout=60,
        check=True,
    )  # fmt: skip
    import json

    from ros2lite.interfaces import type_hash

    origins, hashes = json.loads(proc.stdout)
    assert origins == ['environment', 'environment']
    assert hashes == [type_hash('std_msgs/msg/Header'), type_hash('geometry_msgs/msg/TwistStamped')]
