"""The single-threaded executor and Future: callbacks run on the spinning thread, timeouts are
honoured, and spin_until_future_complete returns when the future is done (or time is up)."""

from __future__ import annotations

import itertools
import threading
import time
from typing import Any

import pytest

import ros2lite
from ros2lite.executor import Future, SingleThreadedExecutor
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from tests.spinning import spin_until, wait_matched


def test_future_result_and_callbacks() -> None:
    fut = Future()
    seen: list[Any] = []
    fut.add_done_callback(lambda f: seen.append(f.result()))
    assert not fut.done() and fut.result() is None
    fut.set_result(5)
    assert fut.done() and fut.result() == 5 and seen == [5]
    fut.add_done_callback(lambda f: seen.append('late'))  # runs at once when already done
    assert seen == [5, 'late']
    assert fut.wait(0) is True


def test_future_exception_and_cancel() -> None:
    fut = Future()
    fut.set_exception(ValueError('boom'))
    with pytest.raises(ValueError, match='boom'):
        fut.result()
    assert isinstance(fut.exception(), ValueError)
    cancelled = Future()
    cancelled.cancel()
    assert cancelled.cancelled() and cancelled.done()
    done = Future()
    done.set_result(1)
    done.cancel()
    assert not done.cancelled()


def test_spin_until_future_complete_with_timer(ros_context: Any) -> None:
    node = Node('futures', context=ros_context)
    fut = Future()
    calls: list[int] = []

    def tick() -> None:
        calls.append(1)
        if len(calls) == 3:
            fut.set_result('done')

    node.create_timer(0.02, tick)
    start = time.monotonic()
    ros2lite.spin_until_future_complete(node, fut, executor=SingleThreadedExecutor(
        context=ros_context), timeout_sec=5)
    assert fut.result() == 'done' and len(calls) == 3
    assert time.monotonic() - start < 1.0


def test_spin_until_future_complete_times_out(ros_context: Any) -> None:
    node = Node('patient', context=ros_context)
    fut = Future()
    start = time.monotonic()
    SingleThreadedExecutor(context=ros_context).add_node(node)
    ros2lite.spin_until_future_complete(node, fut, timeout_sec=0.3)
    elapsed = time.monotonic() - start
    assert not fut.done()
    assert 0.25 <= elapsed < 1.0


def test_future_completed_from_another_thread_wakes_the_executor(ros_context: Any) -> None:
    node = Node('woken', context=ros_context)
    fut = Future()
    threading.Timer(0.1, fut.set_result, args=(1,)).start()
    start = time.monotonic()
    ros2lite.spin_until_future_complete(node, fut, timeout_sec=5)
    assert fut.done() and time.monotonic() - start < 1.0


def test_spin_once_honours_timeout(ros_context: Any) -> None:
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(Node('idle', context=ros_context))
    start = time.monotonic()
    ex.spin_once(timeout_sec=0.2)
    assert 0.15 <= time.monotonic() - start < 0.6
    start = time.monotonic()
    ex.spin_once(timeout_sec=0)
    assert time.monotonic() - start < 0.1


def test_callbacks_run_on_the_spinning_thread(ros_context: Any) -> None:
    node = Node('threads', context=ros_context)
    threads: list[int] = []
    node.create_subscription('std_msgs/msg/String', 'thr', lambda m: threads.append(
        threading.get_ident()), 10)
    pub = node.create_publisher('std_msgs/msg/String', 'thr', 10)
    wait_matched(pub)
    pub.publish(get_interface('std_msgs/msg/String')(data='x'))
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    spin_until(ex, lambda: threads)
    assert threads == [threading.get_ident()]


def test_node_management(ros_context: Any) -> None:
    ex = SingleThreadedExecutor(context=ros_context)
    node = Node('managed', context=ros_context)
    assert ex.add_node(node) is True
    assert ex.add_node(node) is False
    assert ex.get_nodes() == [node]
    ex.remove_node(node)
    assert ex.get_nodes() == []
    ex.add_node(node)
    assert ex.shutdown() is True and ex.get_nodes() == []


def test_module_spin_once_waits_instead_of_busy_looping(ros_context: Any) -> None:
    # each call adds the node to an executor (a wake-up); that alone must not end the wait
    node = Node('looping', context=ros_context)
    start = time.monotonic()
    for _ in range(3):
        ros2lite.spin_once(node, timeout_sec=0.1)
    assert time.monotonic() - start >= 0.25


def _buffered(ros_context: Any, n: int, depth: int = 100) -> tuple[Node, Any, list[str]]:
    """A node whose subscription already holds `n` samples, none delivered yet."""
    String = get_interface('std_msgs/msg/String')
    node = Node('batches', context=ros_context)
    got: list[str] = []
    sub = node.create_subscription(String, 'batch', lambda m: got.append(m.data), depth)
    pub = node.create_publisher(String, 'batch', depth)
    wait_matched(pub)
    for i in range(n):
        pub.publish(String(data=str(i)))
    deadline = time.monotonic() + 5
    while len(sub._buffer) < n:   # (white box) all arrived, none taken
        assert time.monotonic() < deadline
        time.sleep(0.01)
    return node, sub, got


def test_spin_once_runs_exactly_one_callback(ros_context: Any) -> None:
    node, _, got = _buffered(ros_context, 5)
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    ex.spin_once(timeout_sec=1)
    assert got == ['0']
    for _ in range(4):
        ex.spin_once(timeout_sec=1)
    assert got == ['0', '1', '2', '3', '4']


def test_spin_until_future_complete_stops_at_the_completing_callback(ros_context: Any) -> None:
    node, sub, got = _buffered(ros_context, 6)
    fut = Future()
    user_cb = sub.callback

    def completing(msg: Any) -> None:
        user_cb(msg)
        if msg.data == '1':
            fut.set_result(msg.data)

    sub.callback = completing
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    ex.spin_until_future_complete(fut, timeout_sec=5)
    assert fut.result() == '1' and got == ['0', '1']
    spin_until(ex, lambda: len(got) == 6)   # the rest is still delivered later, in order
    assert got == [str(i) for i in range(6)]


def test_timers_are_not_starved_by_a_busy_subscription(ros_context: Any) -> None:
    node, sub, got = _buffered(ros_context, 300, depth=300)
    user_cb = sub.callback

    def slow(msg: Any) -> None:
        time.sleep(0.001)
        user_cb(msg)

    sub.callback = slow
    ticks: list[float] = []
    node.create_timer(0.01, lambda: ticks.append(time.monotonic()))
    fut = Future()
    threading.Timer(0.15, fut.set_result, args=(None,)).start()
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    ex.spin_until_future_complete(fut, timeout_sec=5)
    assert len(got) < 300          # still busy with the backlog…
    assert len(ticks) >= 8         # …yet the 10 ms timer kept firing
    assert max(b - a for a, b in itertools.pairwise(ticks)) < 0.03
