"""tf2 buffer benchmarks: lookups in a buffer that is being fed like a busy robot's.

`tf2_lookup`: 50 frames (a tree up to 7 deep) each sending at 1 kHz, the buffer holding its
full 10 s of history (500,000 samples), while a thread keeps feeding it 50 transforms every
millisecond, as a listener on such a /tf would; the median time of `lookup_transform` between
random frames, at the latest common time and at random times inside the history
(interpolated). Target: under 100 us. Baseline: the same chains multiplied as numpy 4x4
matrices, stored and ready (no search in time, no interpolation, no message built).
`tf2_set_transform`: the cost of storing one transform (what each of the 50,000 a second
costs the listener), against building one TransformStamped message.
`tf2_memory`: bytes a full buffer (10 frames at 1 kHz, fed 2 s past its 10 s) holds per
stored sample (tracemalloc), against the 56 bytes of the sample's seven doubles.
"""

from __future__ import annotations

import math
import random
import threading
import time
import tracemalloc

import numpy as np
from common import rate, report

FRAMES = 50
HZ = 1000
CACHE_S = 10


def _tree(rng: random.Random) -> dict[str, str]:
    """child -> parent for 50 frames under `world`, each parent among the earlier frames but
    kept within depth 7."""
    parent_of: dict[str, str] = {}
    depth = {'world': 0}
    for i in range(FRAMES):
        candidates = [f for f in depth if depth[f] < 7]
        parent = rng.choice(candidates[-8:])  # recent frames: long chains, some branching
        parent_of[f'f{i}'] = parent
        depth[f'f{i}'] = depth[parent] + 1
    return parent_of


def _messages(parent_of: dict[str, str], rng: random.Random) -> list:
    from ros2lite.msgs.geometry_msgs.msg import TransformStamped

    out = []
    for child, parent in parent_of.items():
        t = TransformStamped()
        t.header.frame_id, t.child_frame_id = parent, child
        tr, q = t.transform.translation, t.transform.rotation
        tr.x, tr.y, tr.z = rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)
        v = [rng.gauss(0, 1) for _ in range(4)]
        n = math.sqrt(sum(a * a for a in v))
        q.x, q.y, q.z, q.w = (a / n for a in v)
        out.append(t)
    return out


def _feed(buffer, messages: list, ms_from: int, ms_to: int) -> None:
    for ms in range(ms_from, ms_to):
        sec, nanosec = divmod(1_000_000_000 + ms * 1_000_000, 1_000_000_000)
        for t in messages:
            stamp = t.header.stamp
            stamp.sec, stamp.nanosec = sec, nanosec
            buffer.set_transform(t, 'bench')


def bench_tf2_lookup() -> None:
    from ros2lite.tf2 import BufferCore
    from ros2lite.time import Time

    rng = random.Random(50)
    parent_of = _tree(rng)
    messages = _messages(parent_of, rng)
    buffer = BufferCore()
    full = CACHE_S * HZ
    _feed(buffer, messages, 0, full)
    state = {'ms': full, 'run': True}

    def feeder() -> None:  # 50 transforms every millisecond, paced by the wall clock
        start = time.perf_counter()
        while state['run']:
            _feed(buffer, messages, state['ms'], state['ms'] + 1)
            state['ms'] += 1
            delay = start + (state['ms'] - full) / HZ - time.perf_counter()
            if delay > 0:
                time.sleep(delay)

    thread = threading.Thread(target=feeder, daemon=True)
    thread.start()
    frames = list(parent_of)
    times = []
    began = time.perf_counter()
    try:
        for i in range(4000):
            a, b = rng.sample(frames, 2)
            if i % 2:
                at = Time()
            else:  # inside the history, between two samples
                now = state['ms']
                ms = rng.randint(now - full + 500, now - 500) + rng.random()
                at = Time(nanoseconds=int(1e9 + ms * 1e6))
            t0 = time.perf_counter()
            buffer.lookup_transform_core(a, b, at)
            times.append(time.perf_counter() - t0)
    finally:
        state['run'] = False
        thread.join()
    fed = (state['ms'] - full) * FRAMES / (time.perf_counter() - began)
    ours = sorted(times)[len(times) // 2]

    # the baseline: the same kind of chain as ready 4x4 matrices
    mats = {}
    for t in messages:
        tr, q = t.transform.translation, t.transform.rotation
        m = np.eye(4)
        x, y, z, w = q.x, q.y, q.z, q.w
        m[:3, :3] = [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
        m[:3, 3] = (tr.x, tr.y, tr.z)
        mats[t.child_frame_id] = m

    def up(frame: str) -> np.ndarray:
        m = np.eye(4)
        while frame in parent_of:
            m = mats[frame] @ m
            frame = parent_of[frame]
        return m

    pairs = [rng.sample(frames, 2) for _ in range(200)]
    index = [0]

    def naive() -> None:
        a, b = pairs[index[0] % len(pairs)]
        index[0] += 1
        np.linalg.inv(up(a)) @ up(b)

    base = 1 / rate(naive)
    report('tf2_lookup_median', ours * 1e6, 'us', ours / base)
    # how much was fed meanwhile: 50,000 a second is the load asked for
    report('tf2_lookup_fed_rate', fed, 'tf/s', fed / (FRAMES * HZ))

    # storing one transform, against building one message
    t = messages[-1]
    ms = [state['ms']]

    def store() -> None:
        ms[0] += 1
        stamp = t.header.stamp
        stamp.sec, stamp.nanosec = divmod(1_000_000_000 + ms[0] * 1_000_000, 1_000_000_000)
        buffer.set_transform(t, 'bench')

    from ros2lite.msgs.geometry_msgs.msg import TransformStamped

    ours_set = 1 / rate(store)
    base_set = 1 / rate(TransformStamped)
    report('tf2_set_transform', ours_set * 1e6, 'us', ours_set / base_set)


def bench_tf2_memory() -> None:
    from ros2lite.tf2 import BufferCore

    rng = random.Random(51)
    parent_of = _tree(rng)
    messages = _messages(parent_of, rng)[:10]  # the bytes a sample costs do not need all 50
    tracemalloc.start()
    try:
        before = tracemalloc.get_traced_memory()[0]
        buffer = BufferCore()
        _feed(buffer, messages, 0, CACHE_S * HZ + 2000)  # full, and 2 s past it
        held = tracemalloc.get_traced_memory()[0] - before
    finally:
        tracemalloc.stop()
    samples = sum(len(c) for c in buffer._caches if c is not None)
    assert samples <= len(messages) * (CACHE_S * HZ + 2), samples
    per = held / samples
    report('tf2_memory_per_sample', per, 'bytes', per / 56)


BENCHES = {'tf2_lookup': bench_tf2_lookup, 'tf2_memory': bench_tf2_memory}
