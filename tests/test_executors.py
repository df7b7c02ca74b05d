"""The single-threaded executor and Future: callbacks run on the spinning thread, timeouts are
honoured, and spin_until_future_complete returns when the future is done (or time is up)."""

from __future__ import annotations

import itertools
import threading
import time
from typing import Any

import pytest

import ros2lite
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from ros2lite.task import Future
from tests.spinning import queued, spin_until, wait_matched


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
    ros2lite.spin_until_future_complete(
        node, fut, executor=SingleThreadedExecutor(context=ros_context), timeout_sec=5
    )
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


def test_a_shutdown_whose_wake_up_is_taken_first_ends_the_spin(ros_context: Any) -> None:
    """Found by the churn test (tests/runtime/test_parking.py): a shutdown between spin's look
    at ok() and its look into the queue left only a bare wake-up there, which the fast path
    took as no work and then waited on an empty queue for good."""
    executor = SingleThreadedExecutor(context=ros_context)
    executor.wake()  # the shutdown's wake-up, already queued ...
    executor._is_shutdown = True  # ... when the spin looks into the queue (white box)
    thread = threading.Thread(target=executor.spin_once, daemon=True)
    thread.start()
    thread.join(5)
    assert not thread.is_alive()


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
    node.create_subscription(
        'std_msgs/msg/String', 'thr', lambda m: threads.append(threading.get_ident()), 10
    )
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
    while len(queued(sub)) < n:  # all arrived, none taken
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
    spin_until(ex, lambda: len(got) == 6)  # the rest is still delivered later, in order
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
    assert len(got) < 300  # still busy with the backlog…
    assert len(ticks) >= 8  # …yet the 10 ms timer kept firing
    assert max(b - a for a, b in itertools.pairwise(ticks)) < 0.03


# -- rclpy's concurrency model: executors own their nodes' work, callback groups, tasks --------


def test_each_executor_runs_only_its_own_nodes(ros_context: Any) -> None:
    a, b = Node('exec_a', context=ros_context), Node('exec_b', context=ros_context)
    ran: list[str] = []
    a.create_timer(0.01, lambda: ran.append('a'))
    b.create_timer(0.01, lambda: ran.append('b'))
    first = SingleThreadedExecutor(context=ros_context)
    second = SingleThreadedExecutor(context=ros_context)
    first.add_node(a)
    second.add_node(b)
    assert a.executor is first and b.executor is second
    spin_until(first, lambda: ran.count('a') >= 3)
    assert 'b' not in ran
    spin_until(second, lambda: 'b' in ran)
    # moving a node moves its work
    second.add_node(a)
    assert a.executor is second and first.get_nodes() == []
    ran.clear()
    spin_until(second, lambda: 'a' in ran and 'b' in ran)


def _overlap(executor: Any, node: Node, group_a: Any, group_b: Any) -> int:
    """Most callbacks of two slow timers found running at the same time."""
    running = 0
    most = 0
    lock = threading.Lock()
    calls = itertools.count()

    def slow() -> None:
        nonlocal running, most
        with lock:
            running += 1
            most = max(most, running)
        time.sleep(0.05)
        with lock:
            running -= 1
        next(calls)

    node.create_timer(0.01, slow, callback_group=group_a)
    node.create_timer(0.01, slow, callback_group=group_b)
    executor.add_node(node)
    deadline = time.monotonic() + 10
    while next(calls) < 12 and time.monotonic() < deadline:
        executor.spin_once(timeout_sec=0.05)
    executor.shutdown()
    return most


def test_multithreaded_executor_honours_mutually_exclusive_groups(ros_context: Any) -> None:
    from ros2lite.callback_groups import MutuallyExclusiveCallbackGroup
    from ros2lite.executors import MultiThreadedExecutor

    node = Node('mutex', context=ros_context)
    group = MutuallyExclusiveCallbackGroup()
    assert _overlap(MultiThreadedExecutor(4, context=ros_context), node, group, group) == 1


def test_multithreaded_executor_runs_reentrant_callbacks_in_parallel(ros_context: Any) -> None:
    from ros2lite.callback_groups import ReentrantCallbackGroup
    from ros2lite.executors import MultiThreadedExecutor

    node = Node('reentrant', context=ros_context)
    group = ReentrantCallbackGroup()
    assert _overlap(MultiThreadedExecutor(4, context=ros_context), node, group, group) == 2


def test_single_threaded_executor_never_overlaps(ros_context: Any) -> None:
    from ros2lite.callback_groups import ReentrantCallbackGroup

    node = Node('single', context=ros_context)
    group = ReentrantCallbackGroup()
    assert _overlap(SingleThreadedExecutor(context=ros_context), node, group, group) == 1


def test_coroutine_task_resumes_when_the_awaited_future_completes(ros_context: Any) -> None:
    executor = SingleThreadedExecutor(context=ros_context)
    node = Node('tasks', context=ros_context)
    executor.add_node(node)
    gate = Future()
    steps: list[str] = []

    async def work(x: int) -> int:
        steps.append('start')
        value = await gate
        steps.append('resumed')
        return x + value

    task = executor.create_task(work, 40)
    node.create_timer(0.05, lambda: gate.done() or gate.set_result(2))
    executor.spin_until_future_complete(task, timeout_sec=5)
    assert task.done() and task.result() == 42
    assert steps == ['start', 'resumed']


def test_task_exception_is_raised_from_spin(ros_context: Any) -> None:
    executor = SingleThreadedExecutor(context=ros_context)

    async def fail() -> None:
        raise ValueError('inside the task')

    task = executor.create_task(fail)
    with pytest.raises(ValueError, match='inside the task'):
        executor.spin_once(timeout_sec=1)
    assert isinstance(task.exception(), ValueError)


def test_async_timer_callback_keeps_its_group_until_it_ends(ros_context: Any) -> None:
    """A coroutine callback holds its mutually exclusive group while it awaits, as in rclpy:
    the other timer of the group does not run meanwhile."""
    executor = SingleThreadedExecutor(context=ros_context)
    node = Node('async_timer', context=ros_context)
    gate = Future()
    log: list[str] = []

    async def waiting() -> None:
        log.append('await')
        await gate
        log.append('done')

    first = node.create_timer(0.01, waiting)
    node.create_timer(0.01, lambda: log.append('other'))
    executor.add_node(node)
    spin_until(executor, lambda: 'await' in log)
    first.cancel()
    spin_for_count = 0
    while spin_for_count < 5:
        executor.spin_once(timeout_sec=0.02)
        spin_for_count += 1
    assert 'other' not in log
    gate.set_result(None)
    spin_until(executor, lambda: 'other' in log)
    assert log.index('done') < log.index('other')


def test_shutting_down_a_multithreaded_executor_while_it_spins(ros_context: Any) -> None:
    """shutdown() from another thread ends spin() quietly, even with work still coming in."""
    from ros2lite.executors import MultiThreadedExecutor

    node = Node('busy_mt', context=ros_context)
    ticks = itertools.count()
    node.create_timer(0.0005, lambda: next(ticks))
    executor = MultiThreadedExecutor(2, context=ros_context)
    executor.add_node(node)
    errors: list[BaseException] = []

    def spin() -> None:
        try:
            executor.spin()
        except BaseException as e:  # what an unhandled thread exception would be
            errors.append(e)

    thread = threading.Thread(target=spin)
    thread.start()
    deadline = time.monotonic() + 10
    while next(ticks) < 20 and time.monotonic() < deadline:
        time.sleep(0.01)
    executor.shutdown()
    thread.join(10)
    assert not thread.is_alive() and errors == []


def test_work_taken_just_before_shutdown_is_dropped_cleanly(ros_context: Any) -> None:
    """(white box) the spinning thread may hand over an item it took just before another
    thread shut the pool down: no 'cannot schedule new futures', and the entity's group
    and flag are left free for whoever runs the node next."""
    from ros2lite.executors import MultiThreadedExecutor

    node = Node('late_work', context=ros_context)
    timer = node.create_timer(10.0, lambda: None)
    executor = MultiThreadedExecutor(2, context=ros_context)
    executor.add_node(node)
    executor.shutdown()
    group = timer.callback_group
    assert group.beginning_execution(timer)
    executor._start(timer, group, False, None)
    assert group.can_execute(timer) and not timer.scheduled


def test_spin_once_until_future_complete_ends_when_another_thread_completes_it(
    ros_context: Any,
) -> None:
    node = Node('once_until', context=ros_context)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    future = Future()
    threading.Timer(0.1, future.set_result, args=(True,)).start()
    start = time.monotonic()
    executor.spin_once_until_future_complete(future, timeout_sec=10)
    assert future.done() and time.monotonic() - start < 5


def test_executor_as_context_manager_and_waiting_for_work(ros_context: Any) -> None:
    from ros2lite.executors import ShutdownException, TimeoutException

    with SingleThreadedExecutor(context=ros_context) as executor:
        with pytest.raises(TimeoutException):
            executor.wait_for_ready_callbacks(timeout_sec=0.01)
        task = executor.create_task(lambda: 'done')
        handler, entity, node = executor.wait_for_ready_callbacks(timeout_sec=1)
        assert entity is task and node is None
        handler()
        assert task.result() == 'done'
    with pytest.raises(ShutdownException):
        executor.wait_for_ready_callbacks(timeout_sec=0)


def test_module_spin_once_finds_work_that_came_while_the_node_was_detached(
    ros_context: Any,
) -> None:
    """spin_once(node) adds and removes the node on each call, and add_node looks for work
    that arrived in between only when an entity flagged it: none may be missed."""
    String = get_interface('std_msgs/msg/String')
    node = Node('detached', context=ros_context)
    ran: list[int] = []
    guard = node.create_guard_condition(lambda: ran.append(1))
    ros2lite.spin_once(node, timeout_sec=0.05)  # attached and detached once
    guard.trigger()  # while detached
    start = time.monotonic()
    ros2lite.spin_once(node, timeout_sec=5)
    assert ran == [1] and time.monotonic() - start < 4
    got: list[str] = []
    node.create_subscription(String, 'detached', lambda m: got.append(m.data), 10)
    pub = node.create_publisher(String, 'detached', 10)
    wait_matched(pub)
    ros2lite.spin_once(node, timeout_sec=0.05)
    pub.publish(String(data='x'))
    time.sleep(0.05)  # (arrives while detached, most likely; either order must work)
    start = time.monotonic()
    while not got and time.monotonic() - start < 5:
        ros2lite.spin_once(node, timeout_sec=5)
    assert got == ['x'] and time.monotonic() - start < 4
