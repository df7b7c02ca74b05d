"""Shared memory (issue 38): 1 MiB `sensor_msgs/Image` and 4 MiB `sensor_msgs/PointCloud2`
pub -> sub between two processes, today's path (shared memory off) against shared memory on,
in the same run, next to raw zenoh-python with and without shared memory, a Python memcpy
floor of the same size, and the same rclpy program on real rclpy + Fast DDS (its shared-memory
transport on, as it is by default on one host; confined to loopback as bench_vs_rclpy does it,
skipped with a line when that venv cannot be had). Each figure is the median of ROUNDS
interleaved rounds; MB/s received.

The publisher sends as fast as it can (reliable, keep last 10: congestion drops what the link
cannot take); the subscriber counts the payload bytes it got in WINDOW s after its first.
ros2lite's subscriber deserializes each message (today: `to_bytes()` then CDR), raw zenoh's
calls `to_bytes()` only (and in `raw_zenoh_shm_array` also fills the `array.array` that an
rclpy message's `uint8[]` is: the least a typed subscriber can do), so the gap between the
two is ros2lite's own cost.
"""

from __future__ import annotations

import os
import signal
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from bench_vs_rclpy import Unavailable, confined, real_domain, real_rclpy_python
from common import free_port, report, router_process

ROUNDS = 3
WINDOW = 1.5
SIZES = {'image_1MiB': 1 << 20, 'cloud_4MiB': 4 << 20}
COMPAT = Path(__file__).resolve().parent.parent / 'ros2lite' / 'compat'
SHM_ON = 'transport/shared_memory/enabled=true'

LITE = r'''
import os, sys, time
import rclpy
from rclpy.qos import QoSProfile
from sensor_msgs.msg import Image, PointCloud2
role, size, window = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
kind = Image if size <= (1 << 20) else PointCloud2
rclpy.init()
node = rclpy.create_node('shm_' + role)
qos = QoSProfile(depth=10)
if role == 'sub':
    got = {'n': 0, 'bytes': 0, 't0': 0.0}
    def on(msg):
        if not got['t0']:
            got['t0'] = time.perf_counter()
            return
        got['n'] += 1; got['bytes'] += len(msg.data)
    node.create_subscription(kind, 'shm_flood', on, qos)
    print('ready', flush=True)
    while not got['t0'] or time.perf_counter() - got['t0'] < window:
        rclpy.spin_once(node, timeout_sec=0.05)
    print(got['bytes'] / (time.perf_counter() - got['t0']) / 1e6, flush=True)
    os._exit(0)  # no session teardown while the flood goes on
else:
    pub = node.create_publisher(kind, 'shm_flood', qos)
    msg = kind()
    if kind is Image:
        msg.height, msg.width, msg.encoding, msg.step = 512, 512, 'rgba8', 2048
    else:
        msg.height, msg.width, msg.point_step = 1, size // 16, 16
        msg.row_step = size
    msg.data = bytes(size)
    print('ready', flush=True)
    while True:
        pub.publish(msg)
'''

RAW = r'''
import array, os, sys, time, zenoh
role, size, window, shm = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), sys.argv[4] != '0'
typed = sys.argv[4] == '2'  # the subscriber also fills the array.array an rclpy uint8[] is
link = '["%s"]' % sys.argv[5]  # the subscriber listens, the publisher connects: one link
c = zenoh.Config()
for k, v in (('mode', '"peer"'), ('connect/endpoints', link if role == 'pub' else '[]'),
             ('listen/endpoints', link if role == 'sub' else '[]'),
             ('scouting/multicast/enabled', 'false'),
             ('transport/shared_memory/enabled', 'true' if shm else 'false')):
    c.insert_json5(k, v)
s = zenoh.open(c)
if role == 'sub':
    got = {'n': 0, 'bytes': 0, 't0': 0.0}
    def on(sample):
        data = sample.payload.to_bytes()
        if typed:
            data = array.array('B', data)
        if not got['t0']:
            got['t0'] = time.perf_counter(); return
        got['n'] += 1; got['bytes'] += len(data)
    sub = s.declare_subscriber('raw_flood', on)
    print('ready', flush=True)
    while not got['t0'] or time.perf_counter() - got['t0'] < window:
        time.sleep(0.02)
    print(got['bytes'] / (time.perf_counter() - got['t0']) / 1e6, flush=True)
    os._exit(0)  # no session teardown while the flood goes on
else:
    pub = s.declare_publisher('raw_flood', reliability=zenoh.Reliability.RELIABLE)
    data = bytes(size)
    provider = zenoh.shm.ShmProvider.default_backend(48 << 20) if shm else None
    print('ready', flush=True)
    while True:
        if provider is None:
            pub.put(data)
            continue
        try:
            chunk = provider.alloc(size, zenoh.shm.GarbageCollect())
        except zenoh.ZError:
            pub.put(data); continue
        chunk[:] = data
        pub.put(zenoh.ZBytes(chunk))
'''


def _start(
    code: str, *args: str, env: dict[str, str], python: str = sys.executable
) -> subprocess.Popen[str]:
    proc = subprocess.Popen([python, '-c', code, *args], stdout=subprocess.PIPE, text=True, env=env)
    assert proc.stdout is not None
    if proc.stdout.readline().strip() != 'ready':
        proc.kill()
        raise RuntimeError(f'bench_shm child {args} did not start')
    return proc


def _flow(
    code: str, size: int, env: dict[str, str], *extra: str, python: str = sys.executable
) -> float:
    sub = _start(code, 'sub', str(size), str(WINDOW), *extra, env=env, python=python)
    pub = _start(code, 'pub', str(size), str(WINDOW), *extra, env=env, python=python)
    try:
        out, _ = sub.communicate(timeout=60)
        return float(out.split()[-1])
    finally:
        pub.kill()
        pub.wait()
        if sub.poll() is None:
            sub.kill()
            sub.wait()


def _link() -> str:
    return f'tcp/127.0.0.1:{free_port()}'


def _memcpy(size: int) -> float:
    data = bytes(size)
    n, t0 = 0, time.perf_counter()
    while time.perf_counter() - t0 < 0.3:
        bytearray(data)
        n += 1
    return n * size / (time.perf_counter() - t0) / 1e6


VARIANTS = (
    'lite_today',
    'lite_shm',
    'raw_zenoh',
    'raw_zenoh_shm',
    'raw_zenoh_shm_array',
    'memcpy',
    'real_rclpy',
)
# raw zenoh's subscriber: bytes only (0), with shared memory (1), and with shared memory
# filling the array.array that an rclpy message's uint8[] is (2): ros2lite's floor, since
# zenoh-python 1.10 gives a received payload only as a bytes copy
RAW_MODE = {'raw_zenoh': '0', 'raw_zenoh_shm': '1', 'raw_zenoh_shm_array': '2'}


def _measure(
    variant: str,
    size: int,
    lite_off: dict[str, str],
    lite_on: dict[str, str],
    raw: dict[str, str],
    real: tuple[str, dict[str, str]] | None,
) -> float | None:
    if variant == 'memcpy':
        return _memcpy(size)
    if variant == 'real_rclpy':
        return None if real is None else _flow(LITE, size, real[1], python=real[0])
    if variant.startswith('lite'):
        return _flow(LITE, size, lite_on if variant == 'lite_shm' else lite_off)
    return _flow(RAW, size, raw, RAW_MODE[variant], _link())


def _lite_envs(domain: str) -> tuple[str, dict[str, str], dict[str, str]]:
    """A router endpoint and the rclpy programs' environments on it, shared memory off and on
    (no ZENOH_* of the caller's: only the switch under test differs)."""
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    base = {k: v for k, v in os.environ.items() if not k.startswith('ZENOH_')}
    base.update(
        ROS2LITE_ROUTER=endpoint,
        ROUTER=endpoint,
        ROS_DOMAIN_ID=domain,
        ROS2LITE_NO_DAEMON='1',
        PYTHONPATH=str(COMPAT),
    )
    return endpoint, base, {**base, 'ZENOH_CONFIG_OVERRIDE': SHM_ON}


def bench_shm() -> None:
    endpoint, lite_off, lite_on = _lite_envs('198')
    real: tuple[str, dict[str, str]] | None
    try:
        real = real_rclpy_python(), confined(dict(os.environ), real_domain())
    except Unavailable as e:
        print(f'bench_shm: no real rclpy column: {e}', file=sys.stderr)
        real = None
    figures: dict[str, list[float]] = {}
    with router_process(endpoint):
        for _ in range(ROUNDS):
            for name, size in SIZES.items():
                for variant in VARIANTS:
                    run = _measure(variant, size, lite_off, lite_on, lite_off, real)
                    if run is not None:
                        figures.setdefault(f'{name}_{variant}', []).append(run)
    for name in SIZES:
        today = statistics.median(figures[f'{name}_lite_today'])
        for variant in VARIANTS:
            if f'{name}_{variant}' not in figures:
                continue
            value = statistics.median(figures[f'{name}_{variant}'])
            report(f'shm_{name}_{variant}', value, 'MB/s', value / today if today else 0.0)


CAMERA = r'''
import sys, time
import rclpy
from sensor_msgs.msg import PointCloud2
topic, n, size = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
rclpy.init()
node = rclpy.create_node('shm_camera')
pub = node.create_publisher(PointCloud2, topic, 10)
msg = PointCloud2()
msg.height, msg.width, msg.point_step, msg.row_step = 1, size // 16, 16, size
msg.data = bytes(size)
while pub.get_subscription_count() == 0:
    rclpy.spin_once(node, timeout_sec=0.05)
time.sleep(0.5)  # the recorder subscribes, then discovers: both done
print('start', flush=True)
start = time.perf_counter()
for i in range(n):
    pub.publish(msg)
    time.sleep(max(0.0, start + (i + 1) / 30 - time.perf_counter()))
print('sent', flush=True)
'''
CAMERA_N = 90  # 3 s of a 30 Hz camera


def _cpu_seconds(pid: int) -> float:
    """A live process's user + system CPU so far (all its threads, Zenoh's own included)."""
    fields = Path(f'/proc/{pid}/stat').read_text().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


def _record(env: dict[str, str], directory: str, n: int) -> tuple[int, float]:
    """(messages in the bag, CPU seconds the `bag record` process spent while `n` 4 MiB
    clouds came at 30 Hz and the last reached the disk): read from the live recorder when the
    camera starts and a second after it ends, so its start-up and shutdown are not counted."""
    from ros2lite.bag import Reader

    topic = f'/shm_camera_{time.monotonic_ns()}'
    bag = os.path.join(directory, f'bag_{time.monotonic_ns()}')
    record = [sys.executable, '-m', 'ros2lite', 'bag', 'record', topic, '-o', bag]
    recorder = subprocess.Popen(record, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    args = [sys.executable, '-c', CAMERA, topic, str(n), str(4 << 20)]
    camera = subprocess.Popen(args, env=env, stdout=subprocess.PIPE, text=True)
    assert camera.stdout is not None
    if camera.stdout.readline().strip() != 'start':
        raise RuntimeError('the camera never saw the recorder')
    before = _cpu_seconds(recorder.pid)
    camera.communicate(timeout=120)
    time.sleep(1.0)  # the last ones reach the disk
    cpu = _cpu_seconds(recorder.pid) - before
    recorder.send_signal(signal.SIGINT)
    recorder.communicate(timeout=60)
    with Reader(bag) as reader:
        return reader.message_count, cpu


def bench_shm_record() -> None:
    """`bag record` of a 30 Hz 4 MiB camera, shared memory off and on: the fewest messages a
    round kept (of CAMERA_N), and the recorder's CPU per message kept while recording."""
    endpoint, off, on = _lite_envs('197')
    envs = {'off': off, 'on': on}
    per: dict[str, list[float]] = {k: [] for k in envs}
    kept: dict[str, list[int]] = {k: [] for k in envs}
    with router_process(endpoint), tempfile.TemporaryDirectory() as tmp:
        for _ in range(ROUNDS):
            for mode, env in envs.items():
                count, seconds = _record(env, tmp, CAMERA_N)
                kept[mode].append(count)
                # per message kept (a round that lost some did less work)
                per[mode].append(seconds / max(count, 1) * 1e3)
    for mode in envs:  # a KEEP_LAST publisher drops what a busy link cannot take (rmw_zenoh)
        report(
            f'shm_record_camera_kept_{mode}', min(kept[mode]), 'msgs', min(kept[mode]) / CAMERA_N
        )
    cpu = {mode: statistics.median(per[mode]) for mode in envs}
    report('shm_record_camera_cpu_per_msg_off', cpu['off'], 'ms', 1.0)
    report('shm_record_camera_cpu_per_msg_on', cpu['on'], 'ms', cpu['on'] / cpu['off'])


BENCHES = {'shm': bench_shm, 'shm_record': bench_shm_record}
