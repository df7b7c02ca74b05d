"""An idle single-threaded executor waits in its node's kept channel (no doorbell hand-over per
message), and everything else still reaches it: other work interrupts the wait, deadlines end
it, a node moved to another executor gets its channel back, and no sample is lost."""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator
from typing import Any

import pytest

import ros2lite
from ros2lite.context import Context
from ros2lite.executors import MultiThreadedExecutor, SingleThreadedExecutor
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from ros2lite.qos import QoSProfile
from tests.spinning import wait_matched, wait_until

String = get_interface('std_msgs/msg/String')


@pytest.fixture
def talker(ros_router: str) -> Iterator[Any]:
    """A publisher in a context of its own: samples cross the router's network path."""
    ctx = Context()
    ctx.init([])
    node = Node('park_talker', context=ctx, enable_rosout=False)
    try:
        yield node
    finally:
        ctx.try_shutdown()


class Listener:
    """A subscription whose doorbell notifications are counted (each is a hand-over)."""

    def __init__(self, ctx: Any, topic: str, qos: QoSProfile | int = 10) -> None:
        self.node = Node(f'park_listener_{time.monotonic_ns()}', context=ctx, enable_rosout=False)
        self.got: list[str] = []
        self.threads: set[str] = set()

        def on_msg(msg: Any) -> None:
            self.threads.add(threading.current_thread().name)
            self.got.append(msg.data)

        self.sub = self.node.create_subscription(String, topic, on_msg, qos)
        self.source = self.sub._source
        self.doorbells = 0
        notify = self.source._on_ready

        def counted() -> None:
            self.doorbells += 1
            notify()

        self.source._on_ready = counted


def _listening(ctx: Any, talker: Any, topic: str) -> tuple[Listener, Any, SingleThreadedExecutor]:
    """A counted listener on `topic`, the talker's matched publisher, and a single-threaded
    executor that has the listener's node."""
    listener = Listener(ctx, topic)
    pub = talker.create_publisher(String, topic, 10)
    wait_matched(pub)
    executor = SingleThreadedExecutor(context=ctx)
    executor.add_node(listener.node)
    return listener, pub, executor


def _spin_in_thread(executor: Any) -> threading.Thread:
    thread = threading.Thread(target=executor.spin, daemon=True, name='spinner')
    thread.start()
    return thread


def _send(pub: Any, text: str) -> None:
    pub.publish(String(data=text))


def test_messages_after_the_first_skip_the_doorbell(ros_context: Any, talker: Any) -> None:
    listener, pub, executor = _listening(ros_context, talker, 'park_skip')
    thread = _spin_in_thread(executor)
    try:
        _send(pub, 'first')
        wait_until(lambda: listener.got == ['first'])
        wait_until(lambda: executor._parked is listener.source)
        rung = listener.doorbells
        for i in range(20):
            _send(pub, str(i))
            wait_until(lambda i=i: listener.got[-1:] == [str(i)])
        # every one of them woke the spinning thread straight from the channel
        assert listener.doorbells == rung == 1
        assert listener.threads == {'spinner'}  # callbacks stay on the executor's thread
    finally:
        executor.shutdown()
        thread.join(5)
    assert not thread.is_alive()


def test_other_work_interrupts_the_wait(ros_context: Any, talker: Any) -> None:
    listener, pub, executor = _listening(ros_context, talker, 'park_interrupt')
    thread = _spin_in_thread(executor)
    try:
        _send(pub, 'a')
        wait_until(lambda: executor._parked is listener.source)
        fired = threading.Event()
        guard = listener.node.create_guard_condition(fired.set)
        guard.trigger()  # from this thread, while the executor waits in the channel
        assert fired.wait(5)
        ticks: list[float] = []
        timer = listener.node.create_timer(0.05, lambda: ticks.append(time.monotonic()))
        wait_until(lambda: len(ticks) >= 3)  # the alarm ends each wait at the timer's time
        timer.cancel()  # (a due timer handed the channel back to its doorbell)
        _send(pub, 'b')  # and the channel still delivers afterwards ...
        wait_until(lambda: listener.got == ['a', 'b'])
        wait_until(lambda: executor._parked is listener.source)  # ... and is waited in again
    finally:
        executor.shutdown()
        thread.join(5)
    assert not thread.is_alive()


def test_spin_once_loop_keeps_the_channel_and_honours_its_timeout(
    ros_context: Any, talker: Any
) -> None:
    listener = Listener(ros_context, 'park_once')
    pub = talker.create_publisher(String, 'park_once', 10)
    wait_matched(pub)
    _send(pub, 'first')
    wait_until(
        lambda: listener.got, step=lambda: ros2lite.spin_once(listener.node, timeout_sec=0.05)
    )
    assert listener.source.kept  # spin_once(node) removed the node; the channel stayed
    rung = listener.doorbells
    started = time.monotonic()
    ros2lite.spin_once(listener.node, timeout_sec=0.3)  # nothing comes: the alarm ends it
    waited = time.monotonic() - started
    assert 0.25 <= waited < 3.0
    for i in range(10):
        _send(pub, str(i))
        wait_until(
            lambda i=i: listener.got[-1:] == [str(i)],
            step=lambda: ros2lite.spin_once(listener.node, timeout_sec=1.0),
        )
    assert listener.doorbells == rung


def test_take_outside_spinning_sees_a_kept_channel(ros_context: Any, talker: Any) -> None:
    listener, pub, executor = _listening(ros_context, talker, 'park_take')
    _send(pub, 'first')
    wait_until(lambda: listener.got, step=lambda: executor.spin_once(timeout_sec=0.05))
    assert listener.source.kept
    _send(pub, 'taken')
    taken = wait_until(listener.sub.take)
    assert taken[0].data == 'taken'


def test_a_node_moved_to_a_multithreaded_executor_gets_its_channel_back(
    ros_context: Any, talker: Any
) -> None:
    listener = Listener(ros_context, 'park_move')
    pub = talker.create_publisher(String, 'park_move', 10)
    wait_matched(pub)
    single = SingleThreadedExecutor(context=ros_context)
    single.add_node(listener.node)
    thread = _spin_in_thread(single)
    multi = MultiThreadedExecutor(num_threads=2, context=ros_context)
    try:
        _send(pub, 'a')
        wait_until(lambda: single._parked is listener.source)
        multi.add_node(listener.node)  # taken away mid-wait
        assert not listener.source.kept or single._parked is listener.source
        mthread = threading.Thread(target=multi.spin, daemon=True)
        mthread.start()
        wait_until(lambda: not listener.source.kept)  # the doorbell serves the pool again
        for text in ('b', 'c'):
            _send(pub, text)
            wait_until(lambda text=text: listener.got[-1:] == [text])
        assert single._parked is None
    finally:
        multi.shutdown()
        single.shutdown()
        thread.join(5)
    assert listener.got == ['a', 'b', 'c']


def test_an_interrupt_never_pushes_out_the_newest_sample(ros_context: Any, talker: Any) -> None:
    listener = Listener(ros_context, 'park_depth', qos=1)
    pub = talker.create_publisher(String, 'park_depth', 10)
    wait_matched(pub)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(listener.node)
    _send(pub, 'first')
    wait_until(lambda: listener.got, step=lambda: executor.spin_once(timeout_sec=0.05))
    source = listener.source
    assert source.kept
    _send(pub, 'newest')  # the depth-1 ring holds it, not yet taken ...
    time.sleep(0.3)
    source.arm()
    source.interrupt()  # ... when a late interrupt lands behind it
    source.disarm()
    executor.spin_once(timeout_sec=2.0)
    assert listener.got == ['first', 'newest']


def test_destroying_the_subscription_ends_the_wait(ros_context: Any, talker: Any) -> None:
    listener, pub, executor = _listening(ros_context, talker, 'park_destroy')
    thread = _spin_in_thread(executor)
    try:
        _send(pub, 'a')
        wait_until(lambda: executor._parked is listener.source)
        listener.node.destroy_subscription(listener.sub)
        wait_until(lambda: executor._parked is None)
        ticks: list[int] = []
        listener.node.create_timer(0.02, lambda: ticks.append(1))
        wait_until(lambda: len(ticks) >= 2)  # the executor went on with the node's work
    finally:
        executor.shutdown()
        thread.join(5)
    assert not thread.is_alive()


def test_a_polling_loop_looks_into_the_kept_channel(ros_context: Any, talker: Any) -> None:
    """`spin_once(timeout_sec=0)` never waits, so it looks into the kept channel itself."""
    listener, pub, executor = _listening(ros_context, talker, 'park_poll')
    _send(pub, 'first')
    wait_until(lambda: listener.got, step=lambda: executor.spin_once(timeout_sec=0.05))
    assert listener.source.kept
    for i in range(5):
        _send(pub, str(i))
        wait_until(
            lambda i=i: listener.got[-1:] == [str(i)],
            step=lambda: executor.spin_once(timeout_sec=0),
        )
    assert listener.source.kept


def test_a_subscription_destroyed_mid_callback_is_not_kept(ros_context: Any, talker: Any) -> None:
    """Destroyed while its callback runs: its channel is not kept afterwards, so the idle
    executor does not keep waking up in a closed channel."""
    listener = Listener(ros_context, 'park_destroy_mid')
    inside, leave = threading.Event(), threading.Event()

    def slow(msg: Any) -> None:
        inside.set()
        leave.wait(5)

    sub = listener.node.create_subscription(String, 'park_destroy_mid_slow', slow, 10)
    pub = talker.create_publisher(String, 'park_destroy_mid_slow', 10)
    wait_matched(pub)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(listener.node)
    turns = [0]
    park = executor._park

    def counted(wait: Any) -> Any:
        turns[0] += 1
        return park(wait)

    executor._park = counted  # type: ignore[method-assign]
    thread = _spin_in_thread(executor)
    try:
        _send(pub, 'x')
        assert inside.wait(5)
        listener.node.destroy_subscription(sub)  # while its callback runs
        leave.set()
        time.sleep(0.3)
        before = turns[0]
        time.sleep(0.5)
        assert turns[0] - before < 20  # idle, not spinning on a closed channel
        assert sub._source is not None and not sub._source.kept
    finally:
        leave.set()
        executor.shutdown()
        thread.join(5)


def test_a_topic_with_two_local_subscriptions_is_never_parked_in(
    ros_context: Any, talker: Any
) -> None:
    """An interrupt reaches every subscriber of its key in the session, so a channel is kept
    only by a key's sole subscriber: a second, depth-1 subscription keeps its newest sample."""
    first = Listener(ros_context, 'park_shared')
    second = Listener(ros_context, 'park_shared', qos=1)
    pub = talker.create_publisher(String, 'park_shared', 10)
    wait_matched(pub, 2)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(first.node)
    _send(pub, 'r1')
    wait_until(lambda: first.got, step=lambda: executor.spin_once(timeout_sec=0.05))
    assert not first.source.kept
    _send(pub, 'r2')
    wait_until(lambda: first.got == ['r1', 'r2'], step=lambda: executor.spin_once(timeout_sec=0.05))
    for _ in range(3):  # work elsewhere while the executor waits
        guard = first.node.create_guard_condition(lambda: None)
        guard.trigger()
        executor.spin_once(timeout_sec=0.05)
    assert not first.source.kept
    other = SingleThreadedExecutor(context=ros_context)
    other.add_node(second.node)
    # the newest sample was not pushed out of the depth-1 subscription's channel (under load
    # its doorbell may still hand r1 over first)
    wait_until(lambda: 'r2' in second.got, step=lambda: other.spin_once(timeout_sec=0.05))


def test_a_kept_channel_is_not_starved_by_a_busy_executor(ros_context: Any, talker: Any) -> None:
    """While other work keeps the executor busy, a kept channel goes back to its doorbell, so
    its sample is queued behind that work instead of waiting until the executor is idle."""
    quick = Listener(ros_context, 'park_starve_quick')
    busy: list[str] = []

    def slow(msg: Any) -> None:
        busy.append(msg.data)
        time.sleep(0.05)

    quick.node.create_subscription(String, 'park_starve_busy', slow, QoSProfile(depth=200))
    pub_quick = talker.create_publisher(String, 'park_starve_quick', 10)
    pub_busy = talker.create_publisher(String, 'park_starve_busy', QoSProfile(depth=200))
    wait_matched(pub_quick)
    wait_matched(pub_busy)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(quick.node)
    thread = _spin_in_thread(executor)
    try:
        _send(pub_quick, 'first')
        wait_until(lambda: executor._parked is quick.source)
        for i in range(100):  # five seconds of work for the executor
            _send(pub_busy, str(i))
        wait_until(lambda: busy)
        _send(pub_quick, 'second')
        wait_until(lambda: quick.got == ['first', 'second'], timeout=2.0)
        assert len(busy) < 100  # it came while the backlog was still being worked off
    finally:
        executor.shutdown()
        thread.join(10)


@pytest.mark.parametrize('way_out', ['stop', 'terminate', 'shutdown'])
def test_every_way_out_ends_the_wait_at_once(ros_context: Any, talker: Any, way_out: str) -> None:
    """A program's ways out each end a spin parked in a channel (which has no timeout of its
    own): the key loop's BackgroundSpin.stop, Ctrl-C or SIGTERM (the context terminates), and
    the context's shutdown (which closes the channel)."""
    from ros2lite.bundled.teleop.spinning import BackgroundSpin

    listener = Listener(ros_context, f'park_exit_{way_out}')
    pub = talker.create_publisher(String, f'park_exit_{way_out}', 10)
    wait_matched(pub)
    spin = BackgroundSpin(listener.node)
    with spin:
        _send(pub, 'a')
        wait_until(lambda: spin.executor._parked is listener.source)
        {
            'stop': spin.executor.shutdown,
            'terminate': ros_context.terminate,
            'shutdown': ros_context.try_shutdown,
        }[way_out]()
        spin._thread.join(2.0)
        assert not spin._thread.is_alive()
