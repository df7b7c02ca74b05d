"""The daemon's files: one set per endpoint in the private runtime dir, found without zenoh."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from ros2lite.daemon import paths


def test_one_set_of_files_per_endpoint(runtime: Path) -> None:
    a, b = 'tcp/127.0.0.1:7447', 'tcp/127.0.0.1:7448'
    names = [f(a) for f in (paths.pid_file, paths.log_file, paths.lock_file, paths.graph_socket)]
    assert [p.parent for p in names] == [runtime] * 4
    assert [p.suffix for p in names] == ['.pid', '.log', '.lock', '.sock']
    assert len({p.stem for p in names}) == 1 and paths.pid_file(b) != paths.pid_file(a)
    assert '/' not in paths.stem('unixsock-stream//tmp/x sock')


def test_finding_them_loads_no_zenoh(runtime: Path) -> None:
    code = (
        'import sys; from ros2lite.daemon.paths import graph_socket; '
        'graph_socket("tcp/127.0.0.1:1"); print("zenoh" in sys.modules)'
    )
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == 'False'
