"""The buffer, without a network: lookups along random frame trees against an independent
oracle (transforms3d matrices, slerp by axis and angle), tf2's errors and texts, Time(0) as
the latest common time, memory bounded by the cache length; and futures, one awaited in an
executor."""

from __future__ import annotations

import math
import random
import re
import threading
import tracemalloc
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest
from transforms3d import affines, quaternions

from ros2lite.duration import Duration
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.node import Node
from ros2lite.tf2 import (
    Buffer,
    BufferCore,
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
)
from ros2lite.time import Time
from tests.spinning import spin_until

NS = 1_000_000_000


def stamped(
    parent: str,
    child: str,
    ns: int,
    xyz: tuple[float, float, float] = (0.0, 0.0, 0.0),
    q: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0),
) -> TransformStamped:
    t = TransformStamped()
    t.header.frame_id = parent
    t.child_frame_id = child
    t.header.stamp.sec, t.header.stamp.nanosec = divmod(ns, NS)
    tr, rot = t.transform.translation, t.transform.rotation
    tr.x, tr.y, tr.z = xyz
    rot.x, rot.y, rot.z, rot.w = q
    return t


def unit_quat(rng: random.Random) -> tuple[float, float, float, float]:
    q = np.array([rng.gauss(0, 1) for _ in range(4)])
    q /= np.linalg.norm(q)
    return (float(q[0]), float(q[1]), float(q[2]), float(q[3]))


def oracle_matrix(samples: list[tuple[int, tuple, tuple]], ns: int) -> np.ndarray:
    """parent_T_child at ns from two samples: translation linear, rotation along the shorter
    arc at constant angular speed (axis-angle, not tf2's sine formula)."""
    (t0, p0, q0), (t1, p1, q1) = samples
    ratio = (ns - t0) / (t1 - t0)
    p = np.array(p0) + (np.array(p1) - np.array(p0)) * ratio
    a = np.array([q0[3], *q0[:3]])
    b = np.array([q1[3], *q1[:3]])
    if np.dot(a, b) < 0:
        b = -b
    axis, angle = quaternions.quat2axangle(quaternions.qmult(quaternions.qinverse(a), b))
    q = quaternions.qmult(a, quaternions.axangle2quat(axis, angle * ratio))
    return affines.compose(p, quaternions.quat2mat(q), np.ones(3))


def world(frame: str, parent_of: dict[str, str], history: dict[str, list], ns: int) -> np.ndarray:
    """root_T_frame by the oracle, multiplying matrices up the tree."""
    m = np.eye(4)
    while frame in parent_of:
        m = oracle_matrix(history[frame], ns) @ m
        frame = parent_of[frame]
    return m


def as_matrix(t: TransformStamped) -> np.ndarray:
    tr, r = t.transform.translation, t.transform.rotation
    rot = quaternions.quat2mat([r.w, r.x, r.y, r.z])
    return affines.compose([tr.x, tr.y, tr.z], rot, np.ones(3))


def test_random_chains_agree_with_the_oracle_to_1e_9() -> None:
    rng = random.Random(2727)
    worst = 0.0
    for case in range(1000):
        n = rng.randint(3, 6)  # frames on the chain from source to target
        up = rng.randint(0, n - 1)  # source's side: this many frames below the common one
        names = [f'c{case}_{i}' for i in range(n + 1)]
        # the chain: names[0..up-1] climb to names[up] (common); names[up+1..n-1] climb down
        # to target names[n-1]; names[n] is a root above the common frame
        parent_of = {names[i]: names[i + 1] for i in range(up)}
        parent_of.update({names[i]: names[i - 1] for i in range(up + 1, n)})
        parent_of[names[up]] = names[n]
        if up + 1 < n:
            parent_of[names[up + 1]] = names[up]
        buffer = BufferCore()
        history: dict[str, list[tuple[int, tuple, tuple]]] = {}
        lo, hi = 0, 1 << 62
        for child, parent in parent_of.items():
            t0 = rng.randint(1 * NS, 2 * NS)  # every frame's span holds [2 s, 3 s]
            t1 = rng.randint(3 * NS, 5 * NS)
            samples = []
            for ns in (t1, t0):  # newest first: insertion order must not matter
                xyz = (rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-3, 3))
                samples.append((ns, xyz, unit_quat(rng)))
                assert buffer.set_transform(stamped(parent, child, ns, *samples[-1][1:]), 'x')
            history[child] = samples[::-1]
            lo, hi = max(lo, t0), min(hi, t1)
        ns = rng.randint(lo, hi)

        source, target = names[0], names[n - 1]
        want = np.linalg.inv(world(target, parent_of, history, ns)) @ world(
            source, parent_of, history, ns
        )
        got = buffer.lookup_transform_core(target, source, Time(nanoseconds=ns))
        assert (got.header.frame_id, got.child_frame_id) == (target, source)
        assert got.header.stamp.sec * NS + got.header.stamp.nanosec == ns
        worst = max(worst, float(np.abs(as_matrix(got) - want).max()))
        back = buffer.lookup_transform_core(source, target, Time(nanoseconds=ns))
        worst = max(worst, float(np.abs(as_matrix(back) @ want - np.eye(4)).max()))
    assert worst < 1e-9, worst


def small_tree() -> BufferCore:
    b = BufferCore(Duration(seconds=10))
    for sec in (10, 11, 12):
        b.set_transform(stamped('world', 'base', sec * NS, (float(sec), 0.0, 0.0)), 'a')
    for sec in (10, 12, 13):
        b.set_transform(stamped('base', 'arm', sec * NS, (0.0, float(sec), 0.0)), 'b')
    b.set_transform_static(stamped('arm', 'tool', 0, (0.0, 0.0, 1.0)), 'c')
    b.set_transform(stamped('elsewhere', 'lost', 11 * NS), 'd')
    return b


def raises(kind: type[Exception], call: Callable[[], object]) -> str:
    with pytest.raises(kind) as info:
        call()
    return str(info.value)


def test_time_zero_is_the_latest_time_the_chain_shares() -> None:
    b = small_tree()
    t = b.lookup_transform_core('world', 'tool', Time())
    assert (t.header.stamp.sec, t.header.stamp.nanosec) == (12, 0)  # base ends at 12, arm 13
    tr = t.transform.translation
    assert (tr.x, tr.y, tr.z) == (12.0, 12.0, 1.0)
    assert b.get_latest_common_time('tool', 'arm') == Time()  # static: no time of its own
    assert b.get_latest_common_time('arm', 'world').nanoseconds == 12 * NS
    half = b.lookup_transform_core('tool', 'world', Time(seconds=11, nanoseconds=NS // 2))
    assert half.transform.translation.x == -11.5
    assert half.transform.translation.y == -11.5


def test_errors_are_tf2s() -> None:
    b = small_tree()
    at = Time(seconds=11)
    assert raises(LookupException, lambda: b.lookup_transform_core('world', 'ghost', at)) == (
        '"ghost" passed to lookupTransform argument source_frame does not exist. '
    )
    assert raises(ConnectivityException, lambda: b.lookup_transform_core('world', 'lost', at)) == (
        "Could not find a connection between 'world' and 'lost' because they are not part of "
        'the same tree.Tf has two or more unconnected trees.'
    )
    future = raises(
        ExtrapolationException, lambda: b.lookup_transform_core('world', 'arm', Time(seconds=14))
    )
    assert future == (
        'Lookup would require extrapolation into the future.  Requested time 14.000000 but the '
        'latest data is at time 13.000000, when looking up transform from frame [arm] to frame '
        '[world]'
    )
    past = raises(
        ExtrapolationException, lambda: b.lookup_transform_core('tool', 'world', Time(seconds=9))
    )
    assert past.startswith('Lookup would require extrapolation into the past.  Requested time ')
    assert raises(InvalidArgumentException, lambda: b.lookup_transform_core('/world', 'arm', at))
    assert b.can_transform_core('world', 'ghost', at) == (
        False,
        'Invalid frame ID "ghost" passed to canTransform argument source_frame - frame does not '
        'exist',
    )
    assert b.can_transform_core('world', 'tool', at) == (True, '')
    assert b.can_transform_core('world', 'lost', at)[0] is False
    # data older than the cache length behind the newest is refused, not stored
    assert not b.set_transform(stamped('world', 'base', 1 * NS), 'a')
    # what tf2 refuses outright
    assert not b.set_transform(stamped('world', 'world', 11 * NS), 'a')
    assert not b.set_transform(stamped('world', 'base', 11 * NS, q=(0.0, 0.0, 0.0, 2.0)), 'a')
    assert not b.set_transform(stamped('world', 'base', 11 * NS, (math.nan, 0.0, 0.0)), 'a')


def test_refused_data_is_logged_as_tf2_logs_it(capfd: Any) -> None:
    """tf2's core logs through rcutils' unnamed logger, so its lines carry an empty name."""
    b = small_tree()
    capfd.readouterr()
    assert not b.set_transform(stamped('world', 'base', 1 * NS), 'a')
    assert not b.set_transform(stamped('world', 'world', 11 * NS), 'a')
    err = capfd.readouterr().err.splitlines()
    assert re.fullmatch(
        r'\[WARN\] \[\d+\.\d+\] \[\]: TF_OLD_DATA ignoring data from the past for frame base '
        'at time 1.000000 according to authority a',
        err[0],
    ), err
    assert err[1] == 'Possible reasons are listed at http://wiki.ros.org/tf/Errors%20explained'
    assert re.fullmatch(
        r'\[ERROR\] \[\d+\.\d+\] \[\]: TF_SELF_TRANSFORM: Ignoring transform from authority '
        '"a" with frame_id and  child_frame_id "world" because they are the same',
        err[2],
    ), err


def test_full_lookup_through_a_fixed_frame() -> None:
    b = small_tree()
    # where the tool was at 10 s, seen from the arm at 12 s, with the world fixed
    t = b.lookup_transform_full_core('arm', Time(seconds=12), 'tool', Time(seconds=10), 'world')
    tr = t.transform.translation
    # tool at 10 s in world: (10, 10, 1); arm at 12 s in world: (12, 12, 0)
    assert (tr.x, tr.y, tr.z) == (-2.0, -2.0, 1.0)
    assert b.chain('world', 0, 'tool', 0, 'world') == ['tool', 'arm', 'base', 'world']


def test_frame_parents_is_the_text_as_a_map() -> None:
    """What the views walk (monitor/scene, the rviz2 viewer), without parsing text or YAML."""
    b = small_tree()
    assert b.frame_parents() == {
        'base': 'world',
        'arm': 'base',
        'tool': 'arm',
        'lost': 'elsewhere',
    }


def test_frames_as_text() -> None:
    b = small_tree()
    assert b.all_frames_as_string() == (
        'Frame base exists with parent world.\n'
        'Frame arm exists with parent base.\n'
        'Frame tool exists with parent arm.\n'
        'Frame lost exists with parent elsewhere.\n'
    )
    yaml = b.all_frames_as_yaml()
    assert yaml.startswith(
        "base: \n  parent: 'world'\n  broadcaster: 'a'\n  rate: 1.500\n"
        '  most_recent_transform: 12.000000\n  oldest_transform: 10.000000\n'
        '  buffer_length: 2.000\n'
    )
    assert "tool: \n  parent: 'arm'\n  broadcaster: 'c'\n  rate: 10000.000\n" in yaml
    later = b.all_frames_as_yaml(Time(seconds=15, nanoseconds=250_000_000))
    assert (
        '  oldest_transform: 10.000000\n  transform_delay: 3.250\n  buffer_length: 2.000\n' in later
    )
    assert BufferCore().all_frames_as_yaml() == '[]'
    # every frame named so far, roots too, in the order first heard of (child before parent)
    assert b._getFrameStrings() == ['base', 'world', 'arm', 'tool', 'lost', 'elsewhere']


def test_memory_is_bounded_by_the_cache_length() -> None:
    """A second of history at 1 kHz for 10 frames, fed for 4 seconds: the samples kept and
    the memory held stop growing once the cache is full."""
    b = BufferCore(Duration(seconds=1))
    frames = [stamped('world' if i == 0 else f'f{i - 1}', f'f{i}', 0) for i in range(10)]
    held = []

    def feed(first_ms: int, last_ms: int) -> None:
        for ms in range(first_ms, last_ms):
            ns = NS + ms * 1_000_000
            for t in frames:
                t.header.stamp.sec, t.header.stamp.nanosec = divmod(ns, NS)
                b.set_transform(t, 'feed')

    feed(0, 1000)  # full from here on
    tracemalloc.start()
    try:
        for second in range(1, 4):
            feed(second * 1000, second * 1000 + 1000)
            held.append(tracemalloc.get_traced_memory()[0])
    finally:
        tracemalloc.stop()
    sizes = [len(c) for c in b._caches if c is not None]
    # the newest second, both ends included, and the one sample pruned on the next insert
    assert max(sizes) <= 1002
    # ~70 bytes a sample; pruned room is reused or given back, at most as much again
    assert held[-1] < held[0] * 1.25 + 16_384, held
    assert held[-1] < 10 * 1002 * 72 * 2.5, held
    assert b.lookup_transform_core('world', 'f9', Time()).header.stamp.sec == 4


def test_waiting_and_futures() -> None:
    b = Buffer()
    assert not b.can_transform('world', 'base', Time(), Duration(seconds=0.05))
    future = b.wait_for_transform_async('world', 'base', Time())
    assert not future.done()
    b.set_transform(stamped('world', 'base', 5 * NS, (1.0, 2.0, 3.0)), 'a')
    assert future.done() and future.result().transform.translation.y == 2.0
    assert b._new_data_callbacks == []
    assert b.lookup_transform('world', 'base', Time(), Duration(seconds=1)).header.stamp.sec == 5
    b.clear()  # the frames are still known, their histories are gone
    assert raises(ConnectivityException, lambda: b.lookup_transform('world', 'base', Time()))


def test_a_transform_arriving_while_the_future_is_made_completes_it(monkeypatch: Any) -> None:
    """The one (static) transform may land between the future's first check and its
    registration for new data; the future must still complete, as no second message comes."""
    b = Buffer()
    check = b.can_transform_core
    arrived: list[bool] = []

    def racing(target: str, source: str, time: object) -> tuple[bool, str]:
        result = check(target, source, time)
        if not arrived:  # the listener thread stores it right after this check
            arrived.append(True)
            b.set_transform_static(stamped('world', 'base', 0, (1.0, 0.0, 0.0)), 'a')
        return result

    monkeypatch.setattr(b, 'can_transform_core', racing)
    future = b.wait_for_transform_async('world', 'base', Time())
    assert future.done() and future.result().transform.translation.x == 1.0
    assert b._new_data_callbacks == []


def test_a_future_keeps_its_error_from_the_listener_thread() -> None:
    """A time that is no time fails the future, once; the listener storing transforms later
    never meets the error (it stays registered for no new data)."""
    b = Buffer()
    future = b.wait_for_transform_async('world', 'base', 1.5)
    assert future.done() and isinstance(future.exception(), TypeError)
    assert b._new_data_callbacks == []
    assert b.set_transform(stamped('world', 'base', 5 * NS), 'a')  # no error raised here


def test_lookup_transform_async_resumes_a_coroutine(ros_context: Any) -> None:
    """An async callback awaits a transform that another thread stores later (as the
    listener's would): the executor resumes it with the transform."""
    node = Node('tf2_async_user', context=ros_context)
    b = Buffer(node=node)
    got: list[TransformStamped] = []

    async def once() -> None:
        timer.cancel()
        got.append(await b.lookup_transform_async('world', 'base', Time()))

    timer = node.create_timer(0.01, once)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    try:
        spin_until(executor, lambda: b._new_data_callbacks)  # the coroutine waits
        storer = threading.Thread(
            target=b.set_transform_static, args=(stamped('world', 'base', 0, (4.0, 0, 0)), 'a')
        )
        storer.start()
        storer.join()
        spin_until(executor, lambda: got)
    finally:
        executor.shutdown()
        node.destroy_node()
    assert got[0].transform.translation.x == 4.0
