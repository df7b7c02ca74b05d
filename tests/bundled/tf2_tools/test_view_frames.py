"""`ros2lite run tf2_tools view_frames` against a live broadcaster: it listens, then writes
frames_<date>.gv (tf2_tools' text) and frames_<date>.pdf, which poppler renders with every
frame on it; -o names both files."""

from __future__ import annotations

import re
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

from tests.bundled.tf2_tools.conftest import FRAMES, start_broadcaster
from tests.bundled.tf2_tools.test_frames import ink, needs_poppler, pdf_text

VIEW_FRAMES = [sys.executable, '-m', 'ros2lite', 'run', 'tf2_tools', 'view_frames']


def test_view_frames_writes_both_files(processes: Any, tmp_path: Path) -> None:
    needs_poppler()
    start_broadcaster(processes)
    done = subprocess.run(
        [*VIEW_FRAMES, '--wait-time', '2'], cwd=tmp_path, capture_output=True, text=True
    )
    assert done.returncode == 0, done.stderr
    assert '[view_frames]: Listening to tf data for 2.0 seconds...' in done.stderr
    assert '[view_frames]: Generating graph...' in done.stderr
    names = sorted(p.name for p in tmp_path.iterdir())
    assert len(names) == 2 and all(
        re.fullmatch(r'frames_\d{4}-\d\d-\d\d_\d\d\.\d\d\.\d\d\.(gv|pdf)', n) for n in names
    ), names
    assert f'Exporting graph in {names[1]} file...' in done.stderr
    dot = (tmp_path / names[0]).read_text()
    assert dot.startswith('digraph G {\n') and dot.endswith('}->"world";\n}')
    for parent, child in (('world', 'turtle1'), ('turtle1', 'carrot1'), ('world', 'turtle2')):
        assert f'"{parent}" -> "{child}"[label=" Broadcaster: default_authority\\n' in dot
    rate = re.search(r'"world" -> "turtle1".*?Average rate: ([0-9.]+)', dot)
    assert rate and 10 < float(rate.group(1)) < 30  # sent at 20 Hz
    assert 'Average rate: 10000.0' in dot  # the static frame
    pdf = tmp_path / names[1]
    words = pdf_text(pdf).split()
    assert all(frame in words for frame in FRAMES), words
    assert ink(pdf) > 500

    # -o names both files; --tf_topic listens elsewhere (nothing moves there: the static
    # frame alone is left)
    named = subprocess.run(
        [*VIEW_FRAMES, '-t', '1', '-o', str(tmp_path / 'tree'), '--tf_topic', '/elsewhere'],
        capture_output=True,
        text=True,
    )
    assert named.returncode == 0, named.stderr
    assert (tmp_path / 'tree.pdf').exists()
    dot = (tmp_path / 'tree.gv').read_text()
    assert '"world" -> "turtle2"' in dot and 'turtle1' not in dot


def test_bad_input() -> None:
    done = subprocess.run([*VIEW_FRAMES, '-t', 'soon'], capture_output=True, text=True)
    assert done.returncode == 2 and "'soon' is not a number of seconds" in done.stderr
    done = subprocess.run(
        [*VIEW_FRAMES, '-t', '0', '-o', '/nonexistent/dir/tree'], capture_output=True, text=True
    )
    assert done.returncode == 1 and 'Traceback' not in done.stderr
    assert (
        "cannot write '/nonexistent/dir/tree.gv': No such file or directory"
        in done.stderr.splitlines()
    )


# 2,000 static frames in one message, and one whose name holds an OSC sequence
STAR = r'''
import ros2lite
from ros2lite.executors import ExternalShutdownException
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.node import Node
from ros2lite.tf2 import StaticTransformBroadcaster

def transform(child):
    t = TransformStamped()
    t.header.frame_id = 'map'
    t.child_frame_id = child
    t.transform.rotation.w = 1.0
    return t

with ros2lite.init():
    node = Node('star_broadcaster')
    names = [f'sensor_{i}' for i in range(2000)] + ['evil\x1b]0;PWNED\x07']
    StaticTransformBroadcaster(node).sendTransform([transform(n) for n in names])
    print('broadcasting', flush=True)
    try:
        ros2lite.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
'''


def test_a_big_tree_with_a_hostile_name_is_drawn_and_sigterm_stops_it(
    processes: Any, tmp_path: Path
) -> None:
    star = processes.python(STAR)
    assert star.stdout.readline() == 'broadcasting\n', star.stderr.read()
    started = time.monotonic()
    done = subprocess.run(
        [*VIEW_FRAMES, '-t', '2', '-o', str(tmp_path / 'star')], capture_output=True, text=True
    )
    took = time.monotonic() - started
    assert done.returncode == 0 and 'Traceback' not in done.stderr, done.stderr
    assert took < 90, took  # ~250 s before the layout became linear
    dot = (tmp_path / 'star.gv').read_text()
    assert dot.count('"map" -> ') == 2001
    assert '"map" -> "evil\\\\x1b]0;PWNED\\\\x07"' in dot and '\x1b' not in dot
    # SIGTERM while the picture is made: it ends soon, with nothing half-written
    proc = processes.start([*VIEW_FRAMES, '-t', '2', '-o', str(tmp_path / 'stopped')])
    assert proc.stderr is not None
    generating = threading.Event()

    def drain() -> None:  # (its log must never fill the pipe and block it)
        for line in proc.stderr:
            if 'Generating graph...' in line:
                generating.set()

    threading.Thread(target=drain, daemon=True).start()
    assert generating.wait(60)
    proc.send_signal(signal.SIGTERM)
    stopped = time.monotonic()
    proc.wait(timeout=60)
    assert time.monotonic() - stopped < 30  # it waited 130 s past SIGTERM before
    assert not (tmp_path / 'stopped.pdf').exists()
