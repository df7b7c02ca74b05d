"""Service clients in the library: call_async completed by the executor, blocking call,
timeouts, availability, and rclpy's classic patterns (a service that calls another service)
on the executors that can and cannot run them."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from typing import Any

import pytest

from ros2lite.callback_groups import MutuallyExclusiveCallbackGroup, ReentrantCallbackGroup
from ros2lite.client import ServiceCallError
from ros2lite.executors import MultiThreadedExecutor, SingleThreadedExecutor
from ros2lite.msgs.example_interfaces.srv import AddTwoInts
from ros2lite.msgs.std_srvs.srv import Trigger
from ros2lite.node import Node


def add(request: Any, response: Any) -> Any:
    response.sum = request.a + request.b
    return response


@pytest.fixture
def background() -> Iterator[Any]:
    """Spin executors on background threads; all are shut down at teardown."""
    started: list[tuple[Any, threading.Thread]] = []

    def spin(executor: Any) -> Any:
        thread = threading.Thread(target=executor.spin, daemon=True)
        thread.start()
        started.append((executor, thread))
        return executor

    yield spin
    for executor, thread in started:
        executor.shutdown()
        thread.join(timeout=5)


def test_call_async_completes_on_the_executor(ros_context: Any) -> None:
    node = Node('async_pair', context=ros_context)
    node.create_service(AddTwoInts, 'add_two_ints', add)
    client = node.create_client(AddTwoInts, 'add_two_ints')
    assert client.wait_for_service(timeout_sec=10) and client.service_is_ready()
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    futures = [client.call_async(AddTwoInts.Request(a=i, b=100)) for i in range(5)]
    threads_seen: set[int] = set()
    futures[-1].add_done_callback(lambda f: threads_seen.add(threading.get_ident()))
    for future in futures:
        executor.spin_until_future_complete(future, timeout_sec=10)
    assert [f.result().sum for f in futures] == [100, 101, 102, 103, 104]
    assert threads_seen == {threading.get_ident()}  # done-callbacks ran on the executor


def test_blocking_call_needs_no_executor_for_a_remote_server(
    ros_context: Any, background: Any
) -> None:
    server = Node('remote_server', context=ros_context)
    server.create_service(AddTwoInts, 'add_two_ints', add)
    background(SingleThreadedExecutor(context=ros_context)).add_node(server)
    client = Node('plain_caller', context=ros_context).create_client(AddTwoInts, 'add_two_ints')
    assert client.wait_for_service(timeout_sec=10)
    assert client.call(AddTwoInts.Request(a=2, b=3), timeout_sec=10).sum == 5


def test_untimed_call_waits_on_the_calling_thread_alone(ros_context: Any, background: Any) -> None:
    """`call()` without a timeout waits in Zenoh's reply channel: the answer ends it, and
    so does a missing server for a client that asks to know; no executor is involved."""
    server = Node('untimed_server', context=ros_context)
    server.create_service(AddTwoInts, 'untimed_add', add)
    background(SingleThreadedExecutor(context=ros_context)).add_node(server)
    caller = Node('untimed_caller', context=ros_context)
    client = caller.create_client(AddTwoInts, 'untimed_add')
    assert client.wait_for_service(timeout_sec=10)
    assert [client.call(AddTwoInts.Request(a=i, b=10)).sum for i in range(20)] == [
        i + 10 for i in range(20)
    ]
    assert caller.executor is None  # nobody spun the caller
    eager = caller.create_client(Trigger, 'untimed_nobody', fail_without_server=True)
    start = time.monotonic()
    with pytest.raises(ServiceCallError, match="no server of '/untimed_nobody' answered"):
        eager.call(Trigger.Request())
    assert time.monotonic() - start < 5  # the query ends at once: no queryable matches


def test_untimed_call_nobody_answers_stays_pending_until_ctrl_c(processes: Any) -> None:
    """As with rclpy, `call()` of a service nobody serves waits for good; Ctrl-C ends it
    (the wait is in Zenoh's channel, which gives signals their turn)."""
    code = (
        'import ros2lite, sys\n'
        'from ros2lite.msgs.std_srvs.srv import Trigger\n'
        'ros2lite.init()\n'
        "client = ros2lite.create_node('forever').create_client(Trigger, 'untimed_forever')\n"
        "print('calling', flush=True)\n"
        'try:\n'
        '    client.call(Trigger.Request())\n'
        'except KeyboardInterrupt:\n'
        "    print('interrupted', flush=True)\n"
    )
    proc = processes.python(code)
    assert proc.stdout is not None
    assert proc.stdout.readline().strip() == 'calling'
    time.sleep(1.0)
    assert proc.poll() is None  # still waiting
    out, _ = processes.stop(proc)
    assert 'interrupted' in out


def test_call_timeout_and_unavailable_service(ros_context: Any, background: Any) -> None:
    node = Node('slow_server', context=ros_context)
    release = threading.Event()

    def slow(request: Any, response: Any) -> Any:
        release.wait(10)
        response.success = True
        return response

    node.create_service(Trigger, 'slow', slow)
    background(SingleThreadedExecutor(context=ros_context)).add_node(node)
    caller = Node('impatient', context=ros_context)
    client = caller.create_client(Trigger, 'slow')
    assert client.wait_for_service(timeout_sec=10)
    start = time.monotonic()
    assert client.call(Trigger.Request(), timeout_sec=0.3) is None  # rclpy's timeout
    assert time.monotonic() - start >= 0.3
    release.set()
    nobody = caller.create_client(Trigger, 'nobody_serves_this')
    assert nobody.wait_for_service(timeout_sec=0.2) is False
    assert not nobody.service_is_ready()
    # as in rclpy, a request nobody serves stays pending...
    assert nobody.call(Trigger.Request(), timeout_sec=0.3) is None
    pending = nobody.call_async(Trigger.Request())
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(caller)
    executor.spin_until_future_complete(pending, timeout_sec=0.3)
    assert not pending.done()
    nobody.remove_pending_request(pending)
    # ...unless the client is a tool's that wants to know at once
    eager = caller.create_client(Trigger, 'nobody_serves_this', fail_without_server=True)
    with pytest.raises(ServiceCallError, match="no server of '/nobody_serves_this' answered"):
        eager.call(Trigger.Request(), timeout_sec=10)
    future = eager.call_async(Trigger.Request())
    executor.spin_until_future_complete(future, timeout_sec=10)
    assert isinstance(future.exception(), ServiceCallError)


def test_wrong_request_type_is_a_type_error(ros_context: Any) -> None:
    client = Node('typed', context=ros_context).create_client(AddTwoInts, 'x')
    with pytest.raises(TypeError, match='expected example_interfaces/srv/AddTwoInts_Request'):
        client.call_async(Trigger.Request())


def test_failing_server_callback_raises_from_spin_and_ends_the_query(ros_context: Any) -> None:
    node = Node('failing', context=ros_context)

    def broken(request: Any, response: Any) -> Any:
        raise ValueError('server bug')

    node.create_service(Trigger, 'broken', broken)
    client = node.create_client(Trigger, 'broken')
    assert client.wait_for_service(timeout_sec=10)
    future = client.call_async(Trigger.Request())
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    with pytest.raises(ValueError, match='server bug'):
        executor.spin_until_future_complete(future, timeout_sec=10)
    # the query was ended: a tool's client hears of it at once (a default one keeps waiting)
    eager = node.create_client(Trigger, 'broken', fail_without_server=True)
    future = eager.call_async(Trigger.Request())
    with pytest.raises(ValueError, match='server bug'):
        executor.spin_until_future_complete(future, timeout_sec=10)
    executor.spin_until_future_complete(future, timeout_sec=10)
    assert isinstance(future.exception(), ServiceCallError)


def _outer_calling_inner(node: Node, group: Any) -> Any:
    """`outer` adds 1 to what `inner` returns, calling it with a blocking call."""
    node.create_service(AddTwoInts, 'inner', add, callback_group=group)
    inner = node.create_client(AddTwoInts, 'inner', callback_group=group)

    def outer(request: Any, response: Any) -> Any:
        response.sum = inner.call(request, timeout_sec=10).sum + 1
        return response

    node.create_service(AddTwoInts, 'outer', outer, callback_group=group)
    return node.create_client(AddTwoInts, 'outer')


def test_service_calling_a_service_on_a_multithreaded_executor(
    ros_context: Any, background: Any
) -> None:
    node = Node('classic_mt', context=ros_context)
    outer = _outer_calling_inner(node, ReentrantCallbackGroup())
    background(MultiThreadedExecutor(4, context=ros_context)).add_node(node)
    assert outer.wait_for_service(timeout_sec=10)
    assert outer.call(AddTwoInts.Request(a=1, b=2), timeout_sec=10).sum == 4


def test_the_same_on_one_thread_is_a_clear_error_not_a_hang(ros_context: Any) -> None:
    node = Node('classic_st', context=ros_context)
    outer = _outer_calling_inner(node, None)
    assert outer.wait_for_service(timeout_sec=10)
    future = outer.call_async(AddTwoInts.Request(a=1, b=2))
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    start = time.monotonic()
    with pytest.raises(
        RuntimeError,
        match=r"Client.call\('/inner'\) inside a callback would "
        'deadlock',
    ):
        executor.spin_until_future_complete(future, timeout_sec=10)
    assert time.monotonic() - start < 5


def test_mutually_exclusive_group_on_many_threads_is_refused_too(ros_context: Any) -> None:
    node = Node('classic_mx', context=ros_context)
    outer = _outer_calling_inner(node, MutuallyExclusiveCallbackGroup())
    assert outer.wait_for_service(timeout_sec=10)
    future = outer.call_async(AddTwoInts.Request(a=1, b=2))
    executor = MultiThreadedExecutor(4, context=ros_context)
    executor.add_node(node)
    with pytest.raises(RuntimeError, match='would deadlock'):
        # the worker's error may come just after the outer call's future completes (its
        # query ends with the failed callback): then the next spin raises it
        executor.spin_until_future_complete(future, timeout_sec=10)
        executor.spin_once(timeout_sec=10)
    executor.shutdown()


def test_async_service_callback_awaits_another_service_on_one_thread(ros_context: Any) -> None:
    """The coroutine way: no second thread needed, as long as the inner server is in
    another callback group (the awaiting callback keeps its own group, as in rclpy)."""
    node = Node('async_classic', context=ros_context)
    node.create_service(AddTwoInts, 'inner', add, callback_group=MutuallyExclusiveCallbackGroup())
    inner = node.create_client(AddTwoInts, 'inner')

    async def outer(request: Any, response: Any) -> Any:
        first = await inner.call_async(request)
        second = await inner.call_async(AddTwoInts.Request(a=first.sum, b=1000))
        response.sum = second.sum
        return response

    node.create_service(AddTwoInts, 'outer', outer)
    client = node.create_client(AddTwoInts, 'outer')
    assert client.wait_for_service(timeout_sec=10)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    futures = [client.call_async(AddTwoInts.Request(a=i, b=1)) for i in range(3)]
    for future in futures:
        executor.spin_until_future_complete(future, timeout_sec=10)
    assert [f.result().sum for f in futures] == [1001, 1002, 1003]
