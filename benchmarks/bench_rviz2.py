"""rviz2 benchmarks: a 100k-point PointCloud2 at 10 Hz and a 360-beam LaserScan at 40 Hz into
the browser viewer, drawn by a headless Chromium for the first 8 s, then a browser connection
that stops reading for 10 s.

The viewer runs in this process (ros2lite.bundled.rviz2.viewer, its render loop on a thread,
the node spun in the background as the executable does); the publisher and a baseline
subscription of the scan are processes of their own, on a private router. Chromium
(/usr/bin/chromium, software GL through SwiftShader) is driven over the DevTools protocol; the
first point of each cloud and scan carries the publish's sequence number (exact in viser's
float16 positions), which ties what the browser got back to the header stamp it was sent with.
The publisher stamps with the wall clock; browser times are CLOCK_MONOTONIC (Chromium's
TimeTicks on Linux, time.monotonic() here), moved onto the wall clock by this process's
time.time() - time.monotonic(). Ratios are p95 / p50.

* rviz2_cloud_latency_p50 / _p95: from a cloud's header stamp to the render loop handing its
  drawing to viser's per-client queue (ms), over the whole run (the browser drawing for
  the first 8 s).
* rviz2_cloud_socket_latency_p50 / _p95: from the stamp to the browser's socket receiving the
  frame that carries it (ms; the `timestamp` of Network.webSocketFrameReceived in viser's
  socket worker).
* rviz2_cloud_browser_latency_p50 / _p95: from the stamp to the end of the first animation
  frame after the page got the batch from the worker (ms; a hook on the page's Worker: the
  next requestAnimationFrame, where viser's useFrame drains its queue and three.js draws,
  then a setTimeout(0) after that frame's callbacks; performance.now() put on the monotonic
  clock by the tightest of 20 Runtime.evaluate round trips). Not the compositor's present,
  which would need the Tracing domain.
* rviz2_scan_latency_*, rviz2_scan_socket_latency_*, rviz2_scan_browser_latency_*: the same
  for the scan.
* rviz2_stalled_rss_growth: this process's resident memory after 10 s of a connected client
  that never reads, minus before (MiB); ratio = that / the bytes the publisher sent in those
  10 s (viser keeps the newest message per scene node, so it stays far below 1).
* rviz2_stalled_other_subscriber: scans the baseline subscriber got / scans sent while the
  client was stalled (1: the stalled browser cost the graph nothing); ratio the same.

Only messages that reach each hop count: viser keeps the newest message per scene node for a
client, so a slow page skips clouds and scans (stderr says how many got where, where the
page's time went, and the clock check).

On 2026-12-02 (a 2-core VM shared with other work, load 6-13; five runs, the scan's browser
figures from the last only), p50 / p95 in ms: cloud to viser's queue 53-61 / 115-157, to the
socket 85-109 / 172-264, to the frame 1077-4483 / 1680-6255; scan 43-53 / 96-120, 73-90 /
165-259, 1071 / 1672. Main's version of this benchmark (no browser) gave 42 / 76 and 18 / 35
to the queue that day: the browser's CPU shows in the server-side figures. The frame is
SwiftShader's: the page drew 42-55 animation frames in the 8 s, up to 1.8-4.7 s apart.
"""

from __future__ import annotations

import base64
import contextlib
import itertools
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request
from collections.abc import Callable
from pathlib import Path
from typing import Any

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
    scan = LaserScan()
    scan.header.frame_id = 'map'
    scan.angle_min, scan.angle_increment = -math.pi, 2 * math.pi / 360
    scan.range_min, scan.range_max = 0.1, 30.0
    print('ready', flush=True)
    sys.stdin.readline()
    start = time.monotonic()
    sent_scans = sent_bytes = 0
    tick = 0
    scan_stamps, cloud_stamps = [], []
    while time.monotonic() - start < seconds:
        # the sequence number rides in the first point, which reaches the browser as float16:
        # the cloud's first x is it (exact up to 2048), the scan's first beam (at -pi, so
        # x = -range) is the float16 that many steps above 1.0 (below 16 for 4096 scans)
        first = float(np.array([0x3C00 + tick], np.uint16).view(np.float16)[0])
        scan.ranges = [first] + [2.0] * 359
        if tick % 4 == 0:
            xyz[0, 0] = tick // 4
            cloud.data = xyz.tobytes()
        now = node.get_clock().now().to_msg()
        scan.header.stamp = now
        scan_pub.publish(scan)
        scan_stamps.append(now.sec * 1_000_000_000 + now.nanosec)
        sent_scans += 1
        sent_bytes += 360 * 4
        if tick % 4 == 0:
            cloud.header.stamp = now
            cloud_pub.publish(cloud)
            cloud_stamps.append(now.sec * 1_000_000_000 + now.nanosec)
            sent_bytes += len(cloud.data)
        tick += 1
        time.sleep(max(0.0, start + tick / 40 - time.monotonic()))
    import json
    print(json.dumps({'scans': sent_scans, 'bytes': sent_bytes, 'scan_stamps': scan_stamps,
                      'cloud_stamps': cloud_stamps}), flush=True)
'''


# The browser: headless Chromium on the viewer's page, watched over the DevTools protocol.
HOOK = '''(() => {
  // each batch viser's socket worker hands the page: when it came, and when the first
  // animation frame after it (where viser's useFrame drains its queue and three.js draws)
  // had finished; with the first point of each point cloud it carries
  const seen = (window.__benchFrames = []);
  const ticks = (window.__benchTicks = []);
  const tick = (t) => {
    ticks.push(t);
    requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
  const Base = window.Worker;
  window.Worker = class extends Base {
    constructor(...args) {
      super(...args);
      this.addEventListener('message', (event) => {
        const data = event.data;
        if (!data || data.type !== 'message_batch') return;
        const got = performance.now();
        const hits = [];
        for (const m of data.messages) {
          const p = m.type === 'PointCloudMessage' && m.props ? m.props.points : null;
          if (p && p.length) hits.push([m.name, p[0], p instanceof Uint16Array]);
        }
        if (!hits.length) return;
        requestAnimationFrame(() => {
          const frame = performance.now();
          setTimeout(() => seen.push([got, frame, performance.now(), hits]), 0);
        });
      });
    }
  };
})();'''


class DevTools:
    """A DevTools-protocol connection (flat sessions); events are kept as `on_event` makes
    them (a frame's megabyte of base64 is not kept)."""

    def __init__(self, url: str, on_event: Callable[[dict[str, Any], float], Any]) -> None:
        from websockets.sync.client import connect

        self._ws = connect(url, max_size=None)
        self._on_event = on_event
        self.events: list[Any] = []
        self._results: dict[int, dict[str, Any]] = {}
        self._cond = threading.Condition()
        self._next = 0
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        with contextlib.suppress(Exception):
            for raw in self._ws:
                got = time.monotonic()
                m = json.loads(raw)
                if 'id' in m:
                    with self._cond:
                        self._results[m['id']] = m
                        self._cond.notify_all()
                    continue
                kept = self._on_event(m, got)
                if kept is not None:
                    with self._cond:
                        self.events.append(kept)
                        self._cond.notify_all()

    def call(self, method: str, params: dict[str, Any] | None = None, session: str = '') -> Any:
        with self._cond:
            self._next += 1
            i = self._next
        msg: dict[str, Any] = {'id': i, 'method': method, 'params': params or {}}
        if session:
            msg['sessionId'] = session
        self._ws.send(json.dumps(msg))
        with self._cond:
            if not self._cond.wait_for(lambda: i in self._results, 20):
                raise TimeoutError(method)
            reply = self._results.pop(i)
        if 'error' in reply:
            raise RuntimeError(f'{method}: {reply["error"]}')
        return reply.get('result', {})

    def close(self) -> None:
        self._ws.close()


def _first_points(payload: bytes) -> list[tuple[str, float]]:
    """The first point's x of each point cloud in one of viser's frames: 16 bytes of sizes,
    zstd-compressed msgpack, then the arrays, each 8-byte aligned."""
    import msgspec
    import numpy as np
    import zstandard

    size = int.from_bytes(payload[:8], 'little')
    packed = int.from_bytes(payload[8:16], 'little')
    inner = msgspec.msgpack.decode(
        zstandard.ZstdDecompressor().decompress(payload[16 : 16 + packed], max_output_size=size)
    )
    offsets, at = [], 16 + packed
    for n in inner.get('binaryBufferLengths') or ():
        at = (at + 7) // 8 * 8
        offsets.append(at)
        at += n
    out = []
    for m in inner.get('messages', ()):
        points = m.get('props', {}).get('points') if m.get('type') == 'PointCloudMessage' else None
        if isinstance(points, dict) and '__binary_index' in points:
            dtype = np.dtype(points['dtype'])
            start = offsets[points['__binary_index']]
            out.append((m['name'], float(np.frombuffer(payload, dtype, 1, start)[0])))
    return out


CHROMIUM_FLAGS = (
    '--headless',
    '--no-sandbox',
    '--disable-gpu',
    '--disable-quic',
    '--no-first-run',
    '--disable-background-networking',
    '--disable-component-update',
    '--disable-sync',
    '--use-angle=swiftshader',
    '--enable-unsafe-swiftshader',
    '--window-size=800,600',
    '--remote-debugging-port=0',
)


def _socket_event(m: dict[str, Any], got: float) -> Any:
    """What is kept of an event: a socket frame's arrival (browser's monotonic clock, s)
    and the first points it carries; a request's send time beside when it was seen."""
    method, params = m.get('method'), m.get('params', {})
    if method == 'Network.webSocketFrameReceived' and params['response']['opcode'] == 2:
        payload = base64.b64decode(params['response']['payloadData'])
        return ('frame', params['timestamp'], got, _first_points(payload))
    if method == 'Network.requestWillBeSent':
        return ('request', params['timestamp'], got, params['request']['url'])
    if method == 'Target.attachedToTarget':
        return ('attached', params['sessionId'], got, params['targetInfo']['type'])
    return None


class Browser:
    """Headless Chromium on `url`, its socket worker's frames and the page's animation
    frames recorded; `offset` turns the page's performance.now() (ms) into monotonic s."""

    def __init__(self, url: str) -> None:
        self.home = tempfile.mkdtemp(prefix='bench-rviz2-chromium-')
        self.proc = subprocess.Popen(
            ['/usr/bin/chromium', *CHROMIUM_FLAGS, f'--user-data-dir={self.home}', 'about:blank'],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        active = Path(self.home) / 'DevToolsActivePort'
        deadline = time.monotonic() + 30
        while not (active.exists() and '\n' in active.read_text()):
            if time.monotonic() > deadline:
                raise TimeoutError('chromium wrote no DevToolsActivePort')
            time.sleep(0.05)
        port = int(active.read_text().split()[0])
        with urllib.request.urlopen(f'http://127.0.0.1:{port}/json/list') as r:
            page = next(t for t in json.load(r) if t['type'] == 'page')
        self.cdp = DevTools(page['webSocketDebuggerUrl'], _socket_event)
        self.cdp.call('Network.enable')
        self.cdp.call('Page.enable')
        self.cdp.call('Page.addScriptToEvaluateOnNewDocument', {'source': HOOK})
        # viser's socket lives in a dedicated worker: its Network events are the worker's
        self.cdp.call(
            'Target.setAutoAttach',
            {'autoAttach': True, 'waitForDebuggerOnStart': True, 'flatten': True},
        )
        self.sent = time.monotonic()
        self.cdp.call('Page.navigate', {'url': url})
        sessions: set[str] = set()
        deadline = time.monotonic() + 30
        while not self.frames():
            if time.monotonic() > deadline:
                raise TimeoutError('the page got no frame from the viewer')
            for e in list(self.cdp.events):
                if e[0] == 'attached' and e[1] not in sessions:
                    sessions.add(e[1])
                    self.cdp.call('Network.enable', session=e[1])
                    self.cdp.call('Runtime.runIfWaitingForDebugger', session=e[1])
            time.sleep(0.01)
        self.loaded = time.monotonic()
        # performance.now() against time.monotonic(): the tightest of 20 round trips
        best = (float('inf'), 0.0)
        for _ in range(20):
            before = time.monotonic()
            now = self.cdp.call('Runtime.evaluate', {'expression': 'performance.now()'})
            after = time.monotonic()
            best = min(best, (after - before, (before + after) / 2 - now['result']['value'] / 1e3))
        self.offset_rtt, self.offset = best

    def frames(self) -> list[tuple[float, float, list[tuple[str, float]]]]:
        return [e[1:] for e in list(self.cdp.events) if e[0] == 'frame']

    def clock_check(self) -> str:
        """Whether the browser's Network timestamps read time.monotonic()'s clock: the page
        request's stamp between navigate sent and the first socket frame, the frames' stamps
        just before this process read them."""
        url = next(e for e in self.cdp.events if e[0] == 'request')
        lags = sorted(got - ts for ts, got, _ in self.frames())
        return (
            f'page request stamped {1e3 * (url[1] - self.sent):.1f} ms after navigate was sent '
            f'and {1e3 * (self.loaded - url[1]):.0f} ms before the first frame was in; '
            f'frames read {1e3 * lags[0]:.1f}..{1e3 * statistics.median(lags):.1f} ms '
            f'(min..median) after their stamps'
        )

    def painted(self) -> list[tuple[float, float, float, list[tuple[str, float]]]]:
        """The page's record, in monotonic seconds: (batch in, the next animation frame's
        callbacks begun, that frame done, first points)."""
        got = self.cdp.call(
            'Runtime.evaluate',
            {'expression': 'JSON.stringify(window.__benchFrames)', 'returnByValue': True},
        )
        out = []
        import numpy as np

        for came, frame, done, hits in json.loads(got['result']['value']):
            xs = [
                (name, float(np.array([v], np.uint16).view(np.float16)[0]) if f16 else v)
                for name, v, f16 in hits
            ]
            out.append(
                (self.offset + came / 1e3, self.offset + frame / 1e3, self.offset + done / 1e3, xs)
            )
        return out

    def frame_intervals(self) -> list[float]:
        """The page's animation frames: the time from each to the next (ms)."""
        got = self.cdp.call(
            'Runtime.evaluate',
            {'expression': 'JSON.stringify(window.__benchTicks)', 'returnByValue': True},
        )
        ticks = json.loads(got['result']['value'])
        return [b - a for a, b in itertools.pairwise(ticks)]

    def close(self) -> None:
        with contextlib.suppress(Exception):
            self.cdp.close()
        self.proc.terminate()
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        shutil.rmtree(self.home, ignore_errors=True)


def _seq(kind: str, x: float) -> int:
    """The publisher's code back from a first point's x (see PUBLISHER)."""
    import numpy as np

    if kind == 'cloud':
        return round(x)
    return int(np.array([-x], np.float16).view(np.uint16)[0]) - 0x3C00


def browser_latencies(
    arrivals: list[tuple[float, list[tuple[str, float]]]],
    stamps: dict[str, list[int]],
    wall_minus_mono: float,
) -> dict[str, list[float]]:
    """Per kind, each message's first arrival (monotonic s) minus its header stamp (ms), the
    message found by the sequence number its first point carries."""
    names = {'cloud': 'PointCloud2.points', 'scan': 'LaserScan.scan'}
    out: dict[str, list[float]] = {}
    done: set[tuple[str, int]] = set()
    for at, points in arrivals:
        at_ns = (at + wall_minus_mono) * 1e9
        for name, x in points:
            kind = next((k for k, n in names.items() if n in name), None)
            if kind is None:
                continue
            seq, sent = _seq(kind, x), stamps[kind]
            if not 0 <= seq < len(sent) or (kind, seq) in done:
                continue
            done.add((kind, seq))
            out.setdefault(kind, []).append((at_ns - sent[seq]) / 1e6)
    return out


def _report_percentiles(name: str, values: list[float]) -> None:
    values = sorted(values)
    if not values:
        report(f'{name}_p50', float('nan'), 'ms', float('nan'))
        return
    p50 = statistics.median(values)
    p95 = values[int(0.95 * (len(values) - 1))]
    report(f'{name}_p50', p50, 'ms', p95 / p50 if p50 else float('nan'))
    report(f'{name}_p95', p95, 'ms', p95 / p50 if p50 else float('nan'))


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
            browser = Browser(f'http://127.0.0.1:{port}/')
            stack.callback(browser.close)
            wall_minus_mono = statistics.median(time.time() - time.monotonic() for _ in range(5))
            assert pub.stdin is not None
            pub.stdin.write('go\n')
            pub.stdin.flush()
            time.sleep(8)  # the browser draws the scene meanwhile
            painted = browser.painted()
            intervals = browser.frame_intervals()
            sockets = browser.frames()
            clock = browser.clock_check()
            offset_rtt = browser.offset_rtt
            browser.close()
            # a browser that connects, then never reads its socket again (the client's
            # queue of one frame stops its reading, so the TCP window closes)
            # it says its camera first, as a page does: viser counts a connection as a
            # client (and the viewer sends it its own clouds and scans) only from then on
            sys.path.insert(0, str(ROOT))
            from tests.bundled.rviz2.browser import raw_page

            ws = raw_page(port, max_queue=1)
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
    stamps = {'cloud': sent['cloud_stamps'], 'scan': sent['scan_stamps']}
    at_socket = browser_latencies([(ts, xs) for ts, _, xs in sockets], stamps, wall_minus_mono)
    at_frame = browser_latencies([(p[2], p[3]) for p in painted], stamps, wall_minus_mono)
    at_page = browser_latencies([(p[0], p[3]) for p in painted], stamps, wall_minus_mono)
    at_start = browser_latencies([(p[1], p[3]) for p in painted], stamps, wall_minus_mono)
    for kind, key in (('cloud', 'PointCloud2:/points'), ('scan', 'LaserScan:/scan')):
        _report_percentiles(f'rviz2_{kind}_latency', latencies.get(key, []))
        _report_percentiles(f'rviz2_{kind}_socket_latency', at_socket.get(kind, []))
        _report_percentiles(f'rviz2_{kind}_browser_latency', at_frame.get(kind, []))
        print(
            f'# {kind}: {len(stamps[kind])} sent, {len(latencies.get(key, []))} drawn, '
            f'{len(at_socket.get(kind, []))} at the socket, {len(at_frame.get(kind, []))} '
            'in a frame; medians: the worker handed it to the page '
            f'{statistics.median(at_page.get(kind, [float("nan")])):.0f} ms, the next frame '
            f'began {statistics.median(at_start.get(kind, [float("nan")])):.0f} ms; the '
            f'quickest at the socket {min(at_socket.get(kind, [float("nan")])):.1f} ms',
            file=sys.stderr,
        )
    if intervals:
        print(
            f'# the page drew {len(intervals) + 1} animation frames, '
            f'{statistics.median(intervals):.0f} / {max(intervals):.0f} ms apart (median / max)',
            file=sys.stderr,
        )
    print(
        f'# clock check: {clock}; page clock offset within {offset_rtt * 500:.2f} ms',
        file=sys.stderr,
    )
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
