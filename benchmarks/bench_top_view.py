"""The top view (`python -m ros2lite.bundled.rviz2.top_view`) on a 120x40 pseudo-terminal,
fed a 360-beam LaserScan and an odom -> base_link transform: what it costs, and whether a
flood of scans makes it fall behind or grow.

* top_view_cpu_40hz: the view's CPU (user + system) over a steady 3 s with scans at 40 Hz,
  as % of one core; ratio = that / the 25 % target.
* top_view_redraws_40hz: pictures drawn a second (it draws at most 10); ratio = / 10.
* top_view_cpu_flood: the same with scans as fast as one publisher sends them; ratio = / the
  40 Hz figure (newest-wins: a flood should cost little more than receiving it).
* top_view_flood_rate: the scans a second the publisher sent meanwhile; ratio = / 40.
* top_view_rss_growth_flood: how much the view's resident memory grew between the 2nd and
  the 8th second of the flood, in MB; ratio = / 5 MB (a queue would grow without bound).
"""

from __future__ import annotations

import os
import select
import subprocess
import sys
import time

from bench_plot import cpu_seconds
from bench_topic import private_router
from common import Terminal, report

TARGET_CPU = 0.25

PUBLISHER = r'''
import math, sys, time
from ros2lite.context import Context
from ros2lite.node import Node
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.msgs.sensor_msgs.msg import LaserScan
from ros2lite.tf2 import TransformBroadcaster
hz, seconds = float(sys.argv[1]), float(sys.argv[2])
ctx = Context(); ctx.init([])
node = Node('bench_top_view_publisher', context=ctx, enable_rosout=False)
tf = TransformBroadcaster(node)
pub = node.create_publisher(LaserScan, '/scan', 10)
while pub.get_subscription_count() < 1:
    time.sleep(0.02)
scan = LaserScan()
scan.header.frame_id = 'base_link'
scan.angle_increment = 2 * math.pi / 360
scan.range_min, scan.range_max = 0.1, 10.0
# ten shapes in turn, so every scan changes the picture
shapes = [[2.0 + 0.5 * math.sin(k / 10 + j) for k in range(360)] for j in range(10)]
t = TransformStamped()
t.header.frame_id, t.child_frame_id = 'odom', 'base_link'
t.transform.rotation.w = 1.0
print('start', flush=True)
start = time.monotonic()
sent = 0
last_tf = -1.0
while time.monotonic() - start < seconds:
    now = node.get_clock().now().to_msg()
    if time.monotonic() - last_tf >= 0.05:  # tf at 20 Hz whatever the scan rate
        last_tf = time.monotonic()
        t.header.stamp = now
        tf.sendTransform(t)
    scan.header.stamp = now
    scan.ranges = shapes[sent % 10]
    pub.publish(scan)
    sent += 1
    if hz > 0:
        ahead = start + sent / hz - time.monotonic()
        if ahead > 0:
            time.sleep(ahead)
print('done', sent / (time.monotonic() - start), flush=True)
ctx.shutdown()
'''


def rss_mb(pid: int) -> float:
    with open(f'/proc/{pid}/statm') as f:
        return int(f.read().split()[1]) * os.sysconf('SC_PAGE_SIZE') / 1e6


def trial(hz: float, seconds: float) -> dict[str, float]:
    """The view on a pty while a publisher sends for `seconds` (hz 0: as fast as it can)."""
    with private_router() as env:
        env = {**env, 'TERM': 'xterm-256color', 'ROS2LITE_NO_DAEMON': '1'}
        term = Terminal(
            [sys.executable, '-m', 'ros2lite.bundled.rviz2.top_view', '--no-frames'], env, 40, 120
        )
        view = term.proc
        publisher = subprocess.Popen(
            [sys.executable, '-c', PUBLISHER, str(hz), str(seconds)],
            env=env,
            stdout=subprocess.PIPE,
            text=True,
        )
        assert publisher.stdout is not None
        ready, _, _ = select.select([publisher.stdout], [], [], 30)
        if not ready or publisher.stdout.readline().strip() != 'start':
            publisher.kill()
            view.kill()
            raise RuntimeError('the view never subscribed')
        time.sleep(2.0)
        rss0 = rss_mb(view.pid)
        cpu0, t0, drawn0 = (
            cpu_seconds(view.pid),
            time.monotonic(),
            term.output().count(b'\x1b[J'),
        )
        time.sleep(seconds - 3.0)
        cpu1, t1, drawn1 = (
            cpu_seconds(view.pid),
            time.monotonic(),
            term.output().count(b'\x1b[J'),
        )
        rss1 = rss_mb(view.pid)
        done = publisher.stdout.readline().split()
        publisher.wait(10)
        term.close()
    return {
        'cpu': (cpu1 - cpu0) / (t1 - t0),
        'redraws': (drawn1 - drawn0) / (t1 - t0),
        'rss_growth': rss1 - rss0,
        'sent_rate': float(done[1]),
    }


def bench_top_view() -> None:
    steady = trial(40.0, 6.0)
    report('top_view_cpu_40hz', steady['cpu'] * 100, '%', steady['cpu'] / TARGET_CPU)
    report('top_view_redraws_40hz', steady['redraws'], '/s', steady['redraws'] / 10)
    flood = trial(0.0, 10.0)
    report('top_view_cpu_flood', flood['cpu'] * 100, '%', flood['cpu'] / max(steady['cpu'], 1e-9))
    report('top_view_flood_rate', flood['sent_rate'], 'Hz', flood['sent_rate'] / 40)
    report('top_view_rss_growth_flood', flood['rss_growth'], 'MB', flood['rss_growth'] / 5)


BENCHES = {'top_view': bench_top_view}
