"""The ament_flake8 face: flake8 with ROS's settings behind `main_with_errors(argv=[])`, run
with the flake8 the colcon extra installs (4.0.1 beside PyPI's wheel before Python 3.12, a
current one after); and it steps aside for a real ament_flake8."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from ros2lite.pkg.environment import COMPAT_DIR
from tests.tools.colcon.test_course_workspaces import colcon_site  # noqa: F401 (the extra's packages, a fixture)

RUN = """
import json
from ros2lite.compat.ament_flake8.main import main_with_errors
rc, errors = main_with_errors(argv=[])
print(json.dumps([rc, errors]))
"""


def _run(code: str, cwd: Path, pythonpath: list[str]) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, 'PYTHONPATH': os.pathsep.join(pythonpath)}
    return subprocess.run(
        [sys.executable, '-c', code], cwd=cwd, env=env, capture_output=True, text=True, timeout=120
    )


def test_ros_settings_and_each_problem_returned(tmp_path: Path, colcon_site: Path) -> None:  # noqa: F811
    pkg = tmp_path / 'pkg'
    (pkg / 'pkg').mkdir(parents=True)
    (pkg / 'pkg' / '__init__.py').write_text('')
    # 99 characters pass (ROS's limit), docstrings are pep257's business
    (pkg / 'pkg' / 'node.py').write_text(f"def f():\n    return '{'x' * 86}'\n")
    (pkg / '_build').mkdir()
    (pkg / '_build' / 'gen.py').write_text('import os\n')  # folders starting with _ are left out
    (pkg / 'vendored').mkdir()
    (pkg / 'vendored' / 'AMENT_IGNORE').write_text('')
    (pkg / 'vendored' / 'x.py').write_text('import os\n')
    done = _run(RUN, pkg, [str(colcon_site)])
    assert done.returncode == 0, done.stderr
    *shown, last = done.stdout.splitlines()
    assert json.loads(last) == [0, []]
    assert '2 files checked' in shown and 'No problems found' in shown

    (pkg / 'pkg' / 'bad.py').write_text(f"import os\nx=1\ny = '{'z' * 100}'\n")
    done = _run(RUN, pkg, [str(colcon_site)])
    assert done.returncode == 0, done.stderr
    *shown, last = done.stdout.splitlines()
    assert json.loads(last) == [
        1,
        [
            "./pkg/bad.py:1:1: F401 'os' imported but unused",
            './pkg/bad.py:2:2: E225 missing whitespace around operator',
            './pkg/bad.py:3:100: E501 line too long (106 > 99 characters)',
        ],
    ]
    assert '3 errors' in shown and "'E'-type errors: 2" in shown


def test_a_real_ament_flake8_is_used_where_installed(tmp_path: Path, colcon_site: Path) -> None:  # noqa: F811
    code = 'import ament_flake8.main as m; print(m.__file__)'
    wheel = (colcon_site / 'ament_flake8').is_dir()
    assert wheel == (sys.version_info < (3, 12))
    done = _run(code, tmp_path, [str(COMPAT_DIR), str(colcon_site)])
    assert done.returncode == 0, done.stderr
    where = Path(done.stdout.strip()).parent
    assert where == (colcon_site / 'ament_flake8' if wheel else COMPAT_DIR / 'ament_flake8')
    fake = tmp_path / 'site' / 'ament_flake8'
    fake.mkdir(parents=True)
    (fake / '__init__.py').write_text('')
    (fake / 'main.py').write_text('')
    done = _run(code, tmp_path, [str(COMPAT_DIR), str(tmp_path / 'site')])
    assert Path(done.stdout.strip()) == fake / 'main.py'
