"""Ctrl-C on `ros2lite run` of code written as rclpy's tutorials write it, from a source
workspace: whenever it lands, nothing prints a traceback.

A signal sent to the whole process group (a supervisor, `kill -INT -PGID`) reaches the node
once, not again through `run`'s forwarding during its clean-up; one that lands while the
node's interpreter is still starting waits until the runner can take it."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

import pytest

from tests.pkg.workspaces import write_package
from tests.spinning import wait_until

# the tutorial's shape: try/except KeyboardInterrupt around spin, then destroy_node() and
# shutdown(); its clean-up takes a moment, as a real node's may
TUTORIAL_NODE = '''
import time

import rclpy
from rclpy.node import Node
from std_msgs.msg import String


class MinimalPublisher(Node):

    def __init__(self):
        super().__init__('minimal_publisher')
        self.publisher_ = self.create_publisher(String, 'topic', 10)
        self.timer = self.create_timer(0.1, self.timer_callback)
        self.i = 0

    def timer_callback(self):
        msg = String()
        msg.data = 'Hello World: %d' % self.i
        self.publisher_.publish(msg)
        self.get_logger().info('Publishing: "%s"' % msg.data)
        self.i += 1


def main(args=None):
    rclpy.init(args=args)
    minimal_publisher = MinimalPublisher()
    try:
        rclpy.spin(minimal_publisher)
    except KeyboardInterrupt:
        print('caught', flush=True)
    time.sleep(0.5)
    minimal_publisher.destroy_node()
    rclpy.shutdown()
'''


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    ws = tmp_path / 'ws'
    write_package(
        ws / 'src' / 'py_pubsub',
        'py_pubsub',
        scripts={'talker': 'py_pubsub.publisher_member_function:main'},
        modules={
            'py_pubsub/__init__.py': '',
            'py_pubsub/publisher_member_function.py': TUTORIAL_NODE,
        },
    )
    return ws


def start(processes: Any, ws: Path) -> subprocess.Popen[str]:
    return processes.start(
        [sys.executable, '-m', 'ros2lite', 'run', 'py_pubsub', 'talker'],
        stdin=subprocess.DEVNULL,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        start_new_session=True,  # no terminal: our group is a group of its own
        cwd=ws,
    )


def children(pid: int) -> list[int]:
    try:
        text = Path(f'/proc/{pid}/task/{pid}/children').read_text()
    except OSError:
        return []
    return [int(p) for p in text.split()]


def sigint_in(pid: int, field: str) -> bool:
    """Whether SIGINT is in the process' `field` mask of /proc/PID/status (SigCgt: it has a
    handler, which Python installs early in its start-up, before `site` imports anything;
    SigBlk: it is blocked)."""
    try:
        if b'ros2lite.pkg.runner' not in Path(f'/proc/{pid}/cmdline').read_bytes():
            return False  # not yet exec'd: still a copy of `run`
        status = Path(f'/proc/{pid}/status').read_text()
    except OSError:
        return False
    mask = next(line for line in status.splitlines() if line.startswith(field + ':'))
    return bool(int(mask.split()[1], 16) & (1 << (signal.SIGINT - 1)))


def test_a_group_interrupt_while_spinning_reaches_the_node_once(
    processes: Any, workspace: Path
) -> None:
    proc = start(processes, workspace)
    assert proc.stdout is not None
    deadline = time.monotonic() + 30
    line = ''
    while 'Publishing' not in line and time.monotonic() < deadline:
        line = proc.stdout.readline()
        assert line, 'the node ended before it published'
    # the node got a group of its own, so a group's signal reaches it through `run` only
    (node,) = children(proc.pid)
    assert os.getpgid(node) != os.getpgid(proc.pid)
    os.killpg(proc.pid, signal.SIGINT)  # as a supervisor stops a group
    out = line + proc.communicate(timeout=20)[0]
    assert 'Traceback' not in out and 'caught' in out, out
    assert proc.returncode == 0, out


def test_an_interrupt_during_the_node_start_up_waits_for_the_runner(
    processes: Any, workspace: Path
) -> None:
    proc = start(processes, workspace)
    # the moment the node's interpreter can take a Ctrl-C: its `site` is still loading
    node = wait_until(lambda: children(proc.pid), timeout=20, interval=0.001)[0]
    wait_until(lambda: sigint_in(node, 'SigCgt'), timeout=20, interval=0.0005)
    held = sigint_in(node, 'SigBlk')  # until the runner is ready for it
    os.killpg(proc.pid, signal.SIGINT)
    out = proc.communicate(timeout=20)[0]
    assert held
    assert 'Traceback' not in out and 'Error' not in out, out
    # the Ctrl-C came before the program's own `try`: it ends by SIGINT, quietly
    assert proc.returncode == 128 + signal.SIGINT, out
    assert out.strip().splitlines()[-1] == '[ros2run]: Interrupt'
