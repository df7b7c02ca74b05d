"""The ament_copyright face answers the generated test as ROS's does: `main(argv=[...])`,
0 only when every source file carries a copyright notice and a known licence header."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from ros2lite.compat.ament_copyright.main import main
from ros2lite.pkg.environment import ros_environment

APACHE = """# Copyright 2025 Jane Roe
#
# Licensed under the Apache License, Version 2.0 (the "License");
# you may not use this file except in compliance with the License.
# You may obtain a copy of the License at
#
#     http://www.apache.org/licenses/LICENSE-2.0
#
# Unless required by applicable law or agreed to in writing, software
# distributed under the License is distributed on an "AS IS" BASIS,
# WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
# See the License for the specific language governing permissions and
# limitations under the License.
"""
MIT_CPP = """// Copyright (c) 2023-2025, Jane Roe
//
// Permission is hereby granted, free of charge, to any person obtaining a copy
// of this software and associated documentation files (the "Software"), to deal
// in the Software without restriction, including without limitation the rights
// to use, copy, modify, merge, publish, distribute, sublicense, and/or sell
// copies of the Software, and to permit persons to whom the Software is
// furnished to do so, subject to the following conditions:
//
// The above copyright notice and this permission notice shall be included in
// all copies or substantial portions of the Software.
//
// THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
// IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
// FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
// AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
// LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
// OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN
// THE SOFTWARE.
"""


def _package(tmp_path: Path) -> Path:
    pkg = tmp_path / 'pkg'
    (pkg / 'pkg').mkdir(parents=True)
    (pkg / 'test').mkdir()
    (pkg / 'package.xml').write_text('<package/>')
    (pkg / 'setup.py').write_text('print("not checked beside package.xml")\n')
    (pkg / 'pkg' / '__init__.py').write_text('')
    (pkg / '_hidden').mkdir()
    (pkg / '_hidden' / 'x.py').write_text('x = 1\n')
    return pkg


def test_headers_pass_and_a_missing_notice_fails(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    pkg = _package(tmp_path)
    monkeypatch.chdir(pkg)
    (pkg / 'pkg' / 'node.py').write_text('#!/usr/bin/env python3\n' + APACHE + '\nx = 1\n')
    (pkg / 'test' / 'test_a.cpp').write_text(MIT_CPP + '\nint x;\n')
    assert main(argv=['.', 'test']) == 0
    assert capsys.readouterr().out == 'No problems found, checked 3 files\n'

    (pkg / 'test' / 'test_b.py').write_text('def test():\n    pass\n')
    assert main(argv=['.', 'test', '--verbose']) == 1
    out, err = capsys.readouterr()
    assert out.splitlines() == [
        'pkg/__init__.py: file empty',
        'pkg/node.py: copyright=Jane Roe (2025), license=apache2',
        'test/test_a.cpp: copyright=Jane Roe (2023-2025), license=mit',
    ]
    assert err.splitlines() == [
        'test/test_b.py: could not find copyright notice',
        '1 errors, checked 4 files',
    ]


def test_a_changed_licence_text_is_unknown(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    pkg = _package(tmp_path)
    monkeypatch.chdir(pkg)
    (pkg / 'pkg' / 'node.py').write_text(APACHE.replace('Version 2.0', 'Version 3.0'))
    assert main(argv=['.']) == 1
    assert 'pkg/node.py: copyright=Jane Roe (2025), license=<unknown>' in capsys.readouterr().err


def test_repository_root_needs_licence_and_contributing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    pkg = _package(tmp_path)
    (pkg / '.git').mkdir()
    (pkg / 'LICENSE').write_text(
        (Path(__file__).parents[3] / 'ros2lite/pkg/licenses/BSD-3-Clause.txt').read_text()
    )
    monkeypatch.chdir(pkg)
    assert main(argv=['.', '--xunit-file', str(tmp_path / 'out' / 'copyright.xunit.xml')]) == 1
    assert capsys.readouterr().err.splitlines() == [
        'CONTRIBUTING.md: file not found',
        '1 errors, checked 3 files',
    ]
    xunit = (tmp_path / 'out' / 'copyright.xunit.xml').read_text()
    assert 'testsuite name="out.copyright" tests="3" failures="1"' in xunit
    (pkg / 'CONTRIBUTING.md').write_text('Contributions are licensed as the project is.\n')
    assert main(argv=['.', '--verbose']) == 0
    assert 'LICENSE: bsd_3clause' in capsys.readouterr().out


def test_list_licenses(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(argv=['--list-licenses']) == 0
    assert 'apache2: Apache License, Version 2.0' in capsys.readouterr().out.splitlines()


def test_the_generated_test_without_its_skip_checks_for_real(tmp_path: Path) -> None:
    """`pkg create`'s test_copyright.py, its skip removed, run by pytest in a ROS shell's
    environment: it fails on the generated sources, and passes once they carry headers."""
    src = tmp_path / 'src'
    src.mkdir()
    env = {**os.environ}
    env.update(ros_environment(env))
    created = subprocess.run(
        [
            sys.executable,
            '-m',
            'ros2lite',
            'pkg',
            'create',
            '--build-type',
            'ament_python',
            '--license',
            'Apache-2.0',
            '--node-name',
            'talker',
            'fresh',
        ],
        cwd=src,
        env=env,
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert created.returncode == 0, created.stderr
    pkg = src / 'fresh'
    test = pkg / 'test' / 'test_copyright.py'
    test.write_text(
        ''.join(ln for ln in test.read_text().splitlines(True) if 'mark.skip' not in ln)
    )

    def pytest_run() -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [
                sys.executable,
                '-m',
                'pytest',
                '-q',
                '-p',
                'ament_copyright.pytest_marker',
                'test/test_copyright.py',
            ],
            cwd=pkg,
            env=env,
            capture_output=True,
            text=True,
            timeout=120,
        )

    failed = pytest_run()
    assert failed.returncode == 1, failed.stdout + failed.stderr
    assert 'fresh/talker.py: could not find copyright notice' in failed.stdout
    assert 'Unknown pytest.mark.copyright' not in failed.stdout  # the face's marker plugin
    for path in [pkg / 'fresh' / 'talker.py', *sorted((pkg / 'test').glob('*.py'))]:
        path.write_text(APACHE + '\n' + path.read_text())
    passed = pytest_run()
    assert passed.returncode == 0, passed.stdout + passed.stderr
    assert '1 passed' in passed.stdout
