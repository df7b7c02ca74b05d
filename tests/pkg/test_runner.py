"""`python -m ros2lite.pkg.runner`: a target's status is the process's status, as with its
installed script — including after a Ctrl-C the target caught."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

# a Ctrl-C that lands while generated source runs (as when a message class is made during
# start-up), which the program catches like every demo's main() does
TARGET = '''
import os, signal, sys

SOURCE = 'import os, signal\\nos.kill(os.getpid(), signal.SIGINT)\\nfor _ in range(10**7): pass\\n'

def main():
    try:
        exec(SOURCE)
    except KeyboardInterrupt:
        print('caught', flush=True)
    return int(os.environ.get('STATUS', '0'))

def by_exit():
    sys.exit(main())
'''


def _run(tmp_path: Path, target: str, status: int) -> subprocess.CompletedProcess[str]:
    (tmp_path / 'interrupted_target.py').write_text(TARGET)
    env = {**os.environ, 'PYTHONPATH': str(tmp_path), 'STATUS': str(status)}
    return subprocess.run(
        [sys.executable, '-m', 'ros2lite.pkg.runner', f'interrupted_target:{target}', 'exe'],
        capture_output=True,
        text=True,
        env=env,
        timeout=60,
    )


@pytest.mark.parametrize('target', ['main', 'by_exit'])
@pytest.mark.parametrize('status', [0, 3])
def test_a_caught_ctrl_c_leaves_with_the_targets_status(
    tmp_path: Path, target: str, status: int
) -> None:
    done = _run(tmp_path, target, status)
    assert (done.returncode, done.stdout, done.stderr) == (status, 'caught\n', '')


def test_usage_without_a_target() -> None:
    done = subprocess.run(
        [sys.executable, '-m', 'ros2lite.pkg.runner'], capture_output=True, text=True, timeout=60
    )
    assert done.returncode == 2
    assert done.stderr.startswith('usage: python -m ros2lite.pkg.runner')
