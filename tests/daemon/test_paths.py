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


def test_graph_verbs_without_a_usable_home(tmp_path: Path, ros_context: object) -> None:
    """R-G15: with no usable HOME (and no XDG_RUNTIME_DIR) `topic list` failed with
    '[Errno 13] Permission denied'; it now asks the router as --no-daemon does, and where a
    daemon would have to be started, says why in one line."""
    import os

    from ros2lite.msgs.std_msgs.msg import String
    from ros2lite.node import Node
    from tests.spinning import free_port, wait_until

    (tmp_path / 'file').write_text('')
    env = {k: v for k, v in os.environ.items() if k != 'XDG_RUNTIME_DIR'}
    env['HOME'] = str(tmp_path / 'file' / 'home')  # under a file: nothing can be made there

    def run(*args: str, **extra: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            [sys.executable, '-m', 'ros2lite', *args],
            capture_output=True,
            text=True,
            env={**env, **extra},
            timeout=60,
        )

    node = Node('no_home_test', context=ros_context, enable_rosout=False)  # type: ignore[arg-type]
    try:
        node.create_publisher(String, '/no_home_topic', 10)
        listed = wait_until(
            lambda: (
                (r := run('topic', 'list')).returncode == 0 and '/no_home_topic' in r.stdout.split()
            )
        )
        assert listed
    finally:
        node.destroy_node()
    nobody = run('topic', 'list', ROS2LITE_ROUTER=f'tcp/127.0.0.1:{free_port()}')
    assert nobody.returncode == 1
    assert nobody.stderr == (
        f"no place for ros2lite's files: '{tmp_path}/file/home/.cache/ros2lite' cannot be "
        'created (no usable home directory); set HOME or XDG_RUNTIME_DIR to a directory of '
        'this user\n'
    )
