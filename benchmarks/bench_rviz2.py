"""rviz2 benchmarks: a 100k-point PointCloud2 at 10 Hz and a 360-beam LaserScan at 40 Hz into
the browser viewer, with a browser connection that stops reading for 10 s.

The viewer runs in this process (ros2lite.bundled.rviz2.viewer, its render loop on a thread,
the node spun in the background as the executable does); the publisher and a baseline
subscription of the scan are processes of their own, on a private router.

* rviz2_cloud_latency_p50 / _p95: from a cloud's header stamp to the render loop handing its
  drawing to viser's per-client queue (ms); ratio = p95 / p50. The last hop, viser's socket
  to the browser's frame, is not in it (that needs a client reporting back).
* rviz2_scan_latency_p50 / _p95: the same for the scan.
* rviz2_stalled_rss_growth: this process's resident memory after 10 s of a connected client
  that never reads, minus before (MiB); ratio = that / the bytes the publisher sent in those
  10 s (viser keeps the newest message per scene node, so it stays far below 1).
* rviz2_stalled_other_subscriber: scans the baseline subscriber got / scans sent while the
  client was stalled (1: the stalled browser cost the graph nothing); ratio the same.
"""

from __future__ import annotations

import contextlib
import json
import os
import statistics
import sys
import threading
import time
from pathlib import Path

from bench_foxglove import COUNTER
from bench_topic import private_router
from common import free_port, ready_child, report

ROOT = Path(__file__).resolve().parents[1]

PUBLISHER = r'''
import math, sys, time
import numpy as np
import ros2lite
from ros2lite.msgs.sensor_msgs.msg import LaserScan, PointCloud2, PointField
from ros2lite.node import Node
seconds = float(sys.argv[1])
with ros2lite.init(args=[]):
    node = Node('bench_rviz2_pub', enable_rosout=False)
    cloud_pub = node.create_publisher(PointCloud2, '/points', 5)
    scan_pub = node.create_publisher(LaserScan, '/scan', 5)
    n = 100_000
    xyz = np.random.default_rng(1).random((n, 4), dtype=np.float32) * 10
    cloud = PointCloud2()
    cloud.header.frame_id = 'map'
    cloud.fields = [
        PointField(name=a, offset=4 * i, datatype=7, count=1) for i, a in enumerate('xyz')
    ]
    cloud.height, cloud.width, cloud.point_step, cloud.row_step = 1, n, 16, 16 * n
    cloud.data = xyz.tobytes()
    scan = LaserScan()
    scan.header.frame_id = 'map'
    scan.angle_min, scan.angle_increment = -math.pi, 2 * math.pi / 360
    scan.range_min, scan.range_max = 0.1, 30.0
    scan.ranges = [2.0] * 360
    print('ready', flush=True)
    sys.stdin.readline()
    start = time.monotonic()
    sent_scans = sent_bytes = 0
    tick = 0
    while time.monotonic() - start < seconds:
        now = node.get_clock().now().to_msg()
        scan.header.stamp = now
        scan_pub.publish(scan)
        sent_scans += 1
        sent_bytes += 360 * 4
        if tick % 4 == 0:
            cloud.header.stamp = now
            cloud_pub.publish(cloud)
            sent_bytes += len(cloud.data)
        tick += 1
        time.sleep(max(0.0, start + tick / 40 - time.monotonic()))
    import json
    print(json.dumps({'scans': sent_scans, 'bytes': sent_bytes}), flush=True)
'''


def rss_mib() -> float:
    with open('/proc/self/status') as f:
        for line in f:
            if line.startswith('VmRSS:'):
                return int(line.split()[1]) / 1024
    return 0.0


def _stamp_watch(
    displays: dict[str, object], out: dict[str, list[float]], stop: threading.Event
) -> None:
    """Each time a display draws a newer stamp, how long after that stamp it was (ms)."""
    last: dict[str, int] = {}
    while not stop.is_set():
        for key, d in list(displays.items()):
            ns = getattr(d, 'last_stamp_ns', 0)
            if ns and ns != last.get(key):
                last[key] = ns
                out.setdefault(key, []).append((time.time_ns() - ns) / 1e6)
        time.sleep(0.001)


def bench_rviz2() -> None:
    from websockets.sync.client import connect

    import ros2lite
    from ros2lite.bundled.rviz2.config import Config
    from ros2lite.bundled.rviz2.viewer import Settings, Viewer
    from ros2lite.bundled.teleop.spinning import BackgroundSpin
    from ros2lite.node import Node
    from ros2lite.tf2 import Buffer, TransformListener

    with private_router() as env:
        os.environ.update(env)
        with contextlib.ExitStack() as stack:
            counter = stack.enter_context(
                ready_child(COUNTER, '/scan', 'sensor_msgs/msg/LaserScan', env=env)
            )
            pub = stack.enter_context(ready_child(PUBLISHER, '25', env=env, timeout=60))
            ros2lite.init(args=[])
            node = Node('rviz2', enable_rosout=False)
            buffer = Buffer(node=node)
            TransformListener(buffer, node)
            port = free_port()
            viewer = Viewer(node, buffer, Settings(port=port, fixed_frame='map'), Config())
            spin = stack.enter_context(BackgroundSpin(node))
            del spin
            stop = threading.Event()
            loop = threading.Thread(target=viewer.run, args=(lambda: not stop.is_set(),))
            loop.start()
            latencies: dict[str, list[float]] = {}
            watch = threading.Thread(target=_stamp_watch, args=(viewer.displays, latencies, stop))
            watch.start()
            deadline = time.monotonic() + 20
            while len(viewer.displays) < 4 and time.monotonic() < deadline:
                time.sleep(0.1)
            assert pub.stdin is not None
            pub.stdin.write('go\n')
            pub.stdin.flush()
            time.sleep(8)  # a live client would be here; the render loop runs either way
            # a browser that connects, then never reads its socket again (the client's
            # queue of one frame stops its reading, so the TCP window closes)
            import viser

            ws = connect(
                f'ws://127.0.0.1:{port}',
                subprotocols=[f'viser-v{viser.__version__}'],  # type: ignore[list-item]
                max_size=None,
                max_queue=1,
            )
            time.sleep(2)
            before = rss_mib()
            counted_before = viewer.displays.get('LaserScan:/scan')
            scans_before = getattr(counted_before, 'received', 0)
            time.sleep(10)
            after = rss_mib()
            scans_after = getattr(counted_before, 'received', 0)
            ws.close()
            assert pub.stdout is not None
            sent = json.loads(pub.stdout.readline())
            stop.set()
            loop.join(10)
            watch.join(5)
            viewer.close()
            node.destroy_node()
            ros2lite.shutdown()
        assert counter.stdout is not None
        got = json.loads(counter.stdout.read() or '{}')
    for kind, key in (('cloud', 'PointCloud2:/points'), ('scan', 'LaserScan:/scan')):
        values = sorted(latencies.get(key, []))
        if not values:
            report(f'rviz2_{kind}_latency_p50', float('nan'), 'ms', float('nan'))
            continue
        p50 = statistics.median(values)
        p95 = values[int(0.95 * (len(values) - 1))]
        report(f'rviz2_{kind}_latency_p50', p50, 'ms', p95 / p50 if p50 else float('nan'))
        report(f'rviz2_{kind}_latency_p95', p95, 'ms', p95 / p50 if p50 else float('nan'))
    stalled_bytes = sent['bytes'] * 10 / 25
    growth = after - before
    report('rviz2_stalled_rss_growth', growth, 'MiB', growth * 2**20 / stalled_bytes)
    share = got.get('count', 0) / max(1, sent['scans'])
    report('rviz2_stalled_other_subscriber', share, 'ratio', share)
    print(
        f'# viewer got {scans_after - scans_before} scans while stalled; '
        f'rss {before:.0f} -> {after:.0f} MiB',
        file=sys.stderr,
    )


BENCHES = {'rviz2': bench_rviz2}

if __name__ == '__main__':
    bench_rviz2()
