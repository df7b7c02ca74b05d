"""An idle single-threaded executor waits in its node's kept channel (no doorbell hand-over per
message), and everything else still reaches it: other work interrupts the wait, deadlines end
it, a node moved to another executor gets its channel back, and no sample is lost.

The first tests replay the handshake without a router, with a fake channel and executor; the
rest run real subscriptions against a publisher across the router."""

from __future__ import annotations

import os
import queue
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
from ros2lite.runtime.parking import QUEUE, Alarm, Parking
from ros2lite.runtime.scheduling import Scheduled
from tests.spinning import wait_matched, wait_until

String = get_interface('std_msgs/msg/String')


# -- the handshake alone: fakes, no router ----------------------------------------------------
class FakeChannel:
    """A kept channel whose `park` waits for what the test sends: a sample, an interrupt, or
    the close of an undeclare."""

    def __init__(self) -> None:
        self.kept = True
        self.released = 0
        self.interrupts = 0
        self.parking = threading.Event()  # set while a park waits
        self._inbox: queue.SimpleQueue[str] = queue.SimpleQueue()

    def send(self, what: str = 'sample') -> None:
        self._inbox.put(what)

    def _took(self, what: str) -> bool:
        if what == 'close':
            self.kept = False
        if what == 'sample':
            self.kept = False  # the consumer owns the channel again, a sample pending
            return True
        return False

    def poll(self) -> bool:
        while True:
            try:
                what = self._inbox.get_nowait()
            except queue.Empty:
                return False
            if self._took(what):
                return True

    def park(self) -> bool:
        self.parking.set()
        try:
            return self._took(self._inbox.get(timeout=10))
        finally:
            self.parking.clear()

    def interrupt(self) -> None:
        self.interrupts += 1
        self.send('interrupt')

    def release(self) -> None:
        assert self.kept, 'only a kept channel goes back to its doorbell'
        self.kept = False
        self.released += 1


class FakeExecutor:
    def __init__(self, parks: bool = True) -> None:
        self.parks = parks
        self.wakes = 0
        self.ident = threading.get_ident()

    def keeps_here(self) -> bool:
        return self.parks and threading.get_ident() == self.ident

    def wake(self) -> None:
        self.wakes += 1


class Entity(Scheduled):
    pass


def _kept(executor: FakeExecutor | None = None) -> tuple[Parking, list[Any], Entity, FakeChannel]:
    """A node's Parking attached to `executor`, keeping one entity's channel; the entities
    it queued (`notify`) are listed."""
    queued: list[Any] = []
    parking = Parking(queued.append)
    parking.attach(executor or FakeExecutor())
    entity, channel = Entity(), FakeChannel()
    assert parking.keep(entity, channel)
    return parking, queued, entity, channel


def _waiting(parking: Parking, *args: Any) -> tuple[threading.Thread, list[Any]]:
    """`parking.wait(*args)` on a thread of its own (as the executor's); its outcome listed."""
    outcome: list[Any] = []
    thread = threading.Thread(target=lambda: outcome.append(parking.wait(*args)), daemon=True)
    return thread, outcome


def test_a_sample_wakes_the_park_and_its_entity_runs() -> None:
    executor = FakeExecutor()
    parking, _, entity, channel = _kept(executor)
    assert parking.kept_for(executor) == 1
    channel.send()
    assert parking.wait(executor, None, lambda: True) is entity
    assert parking.kept_for(executor) == 0  # it runs now: the channel is the consumer's


def test_only_a_parking_executor_on_its_own_thread_keeps() -> None:
    entity, channel = Entity(), FakeChannel()
    for executor, thread_ok in ((FakeExecutor(parks=False), True), (FakeExecutor(), False)):
        parking = Parking(lambda e: None)
        parking.attach(executor)
        if not thread_ok:
            executor.ident = -1  # the channel was emptied on another thread
        assert not parking.keep(entity, channel)
    assert not Parking(lambda e: None).keep(entity, channel)  # a node with no executor


def test_work_queued_before_or_during_the_park_ends_it() -> None:
    executor = FakeExecutor()
    parking, _, _entity, channel = _kept(executor)
    # queued before the park armed: the idle check after arming sees it, nothing is waited
    assert parking.wait(executor, None, lambda: False) is QUEUE
    assert channel.interrupts == 0 and channel.kept
    thread, outcome = _waiting(parking, executor, None, lambda: True)
    thread.start()
    assert channel.parking.wait(5)
    assert parking.waiting_in is channel
    parking.interrupt()
    parking.interrupt()  # a second one (another enqueue, the alarm) is not sent
    thread.join(5)
    assert outcome == [None] and channel.interrupts == 1
    assert parking.waiting_in is None and parking.kept_for(executor) == 1  # still kept


def test_an_earlier_parks_interrupt_is_waited_past() -> None:
    executor = FakeExecutor()
    parking, _, entity, channel = _kept(executor)
    channel.send('interrupt')  # late, from a park that had ended already
    channel.send()
    assert parking.wait(executor, None, lambda: True) is entity


def test_the_alarm_ends_a_park_at_its_deadline() -> None:
    executor = FakeExecutor()
    parking, _, entity, channel = _kept(executor)
    start = time.monotonic()
    assert parking.wait(executor, 0.05, lambda: True) is None
    assert 0.04 < time.monotonic() - start < 5
    assert channel.interrupts == 1
    channel.send()  # and the next park, with no deadline, still gets its sample
    assert parking.wait(executor, None, lambda: True) is entity
    parking.close()


def test_a_poll_only_looks() -> None:
    executor = FakeExecutor()
    parking, _, entity, channel = _kept(executor)
    assert parking.wait(executor, 0, lambda: True) is QUEUE  # nothing came: the queue decides
    channel.send()
    assert parking.wait(executor, 0, lambda: True) is entity


def test_two_kept_channels_are_not_parked_in_and_go_back() -> None:
    executor = FakeExecutor()
    parking, _, _, first = _kept(executor)
    second = FakeChannel()
    assert parking.keep(Entity(), second)
    assert parking.kept_for(executor) == 2
    assert parking.wait(executor, None, lambda: True) is QUEUE
    parking.hand_back(executor)
    assert (first.released, second.released) == (1, 1)
    assert not parking.keeps


def test_a_busy_executor_hands_kept_channels_back() -> None:
    """Regression (a kept channel waited 3.5 s behind a busy executor): whenever the executor
    turns to other work it hands its kept channels back, but never the one a park is in."""
    executor = FakeExecutor()
    parking, _, entity, channel = _kept(executor)
    thread, outcome = _waiting(parking, executor, None, lambda: True)
    thread.start()
    assert channel.parking.wait(5)
    parking.hand_back(executor)  # (from the thread that parks: it is not running other work)
    assert channel.released == 0
    channel.send()
    thread.join(5)
    assert outcome == [entity]
    channel.kept = True  # its callback emptied the channel again ...
    assert parking.keep(entity, channel)
    parking.hand_back(executor)  # ... and other work comes: back to the doorbell
    assert channel.released == 1 and parking.kept_for(executor) == 0


def test_an_entity_destroyed_in_its_callback_is_not_kept() -> None:
    """Regression (the executor spun at 100 % CPU on a closed channel): a destroyed entity's
    channel is never kept, one destroyed after keeping is forgotten, and a channel that was
    closed meanwhile is dropped before any park."""
    executor = FakeExecutor()
    parking, _, entity, channel = _kept(executor)
    parking.unkeep(entity)
    assert parking.kept_for(executor) == 0
    entity.destroyed = True
    assert not parking.keep(entity, channel)
    other, closed = Entity(), FakeChannel()
    assert parking.keep(other, closed)
    closed.kept = False  # undeclared without an unkeep
    assert parking.kept_for(executor) == 0
    assert parking.wait(executor, None, lambda: True) is QUEUE  # nothing to wait in


def test_a_move_to_a_multithreaded_executor_mid_park_hands_the_channel_back() -> None:
    """Regression (a race with a move to a MultiThreadedExecutor): the park ends, the channel
    goes back to its doorbell for the new executor, and nothing is run by the old one."""
    single = FakeExecutor()
    parking, queued, _entity, channel = _kept(single)
    other, spare = Entity(), FakeChannel()
    assert parking.keep(other, spare)
    parking.unkeep(other)  # (one kept channel to park in)
    thread, outcome = _waiting(parking, single, None, lambda: True)
    thread.start()
    assert channel.parking.wait(5)
    parking.detach(single)
    parking.attach(FakeExecutor(parks=False))
    thread.join(5)
    assert outcome == [None] and channel.released == 1 and not parking.keeps
    assert queued == []


def test_a_sample_taken_as_the_node_moves_is_queued_where_it_went() -> None:
    single, multi = FakeExecutor(), FakeExecutor(parks=False)
    parking, queued, entity, channel = _kept(single)
    real_interrupt = channel.interrupt
    # the sample is already in the channel when the move's interrupt comes
    channel.interrupt = lambda: None  # type: ignore[method-assign]
    thread, outcome = _waiting(parking, single, None, lambda: True)
    thread.start()
    assert channel.parking.wait(5)
    parking.detach(single)
    parking.attach(multi)
    channel.send()
    thread.join(5)
    channel.interrupt = real_interrupt  # type: ignore[method-assign]
    assert outcome == [None]  # not the old executor's to run ...
    assert queued == [entity] and channel.released == 0  # ... but queued on the new one


def test_a_node_moved_between_parking_executors_wakes_the_new_one() -> None:
    first, second = FakeExecutor(), FakeExecutor()
    parking, queued, _entity, channel = _kept(first)
    thread, outcome = _waiting(parking, first, None, lambda: True)
    thread.start()
    assert channel.parking.wait(5)
    parking.detach(first)
    parking.attach(second)
    thread.join(5)
    assert outcome == [None] and second.wakes == 1  # it may park in the channel now
    second.ident = threading.get_ident()
    assert parking.kept_for(second) == 1 and queued == []


def test_the_alarm_calls_only_the_latest_action_and_closes() -> None:
    alarm = Alarm('test-alarm')
    calls: list[str] = []
    alarm.set(time.monotonic() + 10, lambda: calls.append('late'))
    alarm.set(time.monotonic() + 0.01, lambda: calls.append('soon'))  # earlier: wakes it
    wait_until(lambda: calls == ['soon'])
    alarm.set(time.monotonic() + 0.01, lambda: calls.append('cancelled'))
    alarm.cancel()
    alarm.set(time.monotonic() + 0.01, lambda: calls.append('again'))
    wait_until(lambda: calls == ['soon', 'again'])  # the cancelled one never came first
    alarm.close()


# -- real subscriptions, across the router ----------------------------------------------------


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
        wait_until(lambda: listener.node.parking.waiting_in is listener.source)
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
        wait_until(lambda: listener.node.parking.waiting_in is listener.source)
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
        # ... and is waited in again
        wait_until(lambda: listener.node.parking.waiting_in is listener.source)
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
        wait_until(lambda: listener.node.parking.waiting_in is listener.source)
        multi.add_node(listener.node)  # taken away mid-wait
        assert not listener.source.kept or listener.node.parking.waiting_in is listener.source
        mthread = threading.Thread(target=multi.spin, daemon=True)
        mthread.start()
        wait_until(lambda: not listener.source.kept)  # the doorbell serves the pool again
        for text in ('b', 'c'):
            _send(pub, text)
            wait_until(lambda text=text: listener.got[-1:] == [text])
        assert listener.node.parking.waiting_in is None
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
    source.interrupt()  # ... when a late interrupt lands behind it
    executor.spin_once(timeout_sec=2.0)
    assert listener.got == ['first', 'newest']


def test_destroying_the_subscription_ends_the_wait(ros_context: Any, talker: Any) -> None:
    listener, pub, executor = _listening(ros_context, talker, 'park_destroy')
    thread = _spin_in_thread(executor)
    try:
        _send(pub, 'a')
        wait_until(lambda: listener.node.parking.waiting_in is listener.source)
        listener.node.destroy_subscription(listener.sub)
        wait_until(lambda: listener.node.parking.waiting_in is None)
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
    parking = listener.node.parking
    kept_for = parking.kept_for

    def counted(executor: Any) -> int:
        turns[0] += 1
        return kept_for(executor)

    parking.kept_for = counted  # type: ignore[method-assign]
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
        wait_until(lambda: quick.node.parking.waiting_in is quick.source)
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
        wait_until(lambda: listener.node.parking.waiting_in is listener.source)
        {
            'stop': spin.executor.shutdown,
            'terminate': ros_context.terminate,
            'shutdown': ros_context.try_shutdown,
        }[way_out]()
        spin._thread.join(2.0)
        assert not spin._thread.is_alive()


# rounds of the churn test below; R5-L1 counted 11 failures in 300 (ROS2LITE_CHURN_ROUNDS=3000
# is the full run)
CHURN_ROUNDS = int(os.environ.get('ROS2LITE_CHURN_ROUNDS', '60'))
_CHURN_WAYS = ('destroy_sub', 'destroy_node', 'remove_node', 'in_callback', 'spin_once', 'multi')


def _churn_round(ctx: Any, way: str, errors: list[BaseException]) -> None:
    """One node with a subscription to the 1 kHz talker, spun on a thread, and taken away
    while it spins, `way` decides how; what the spinning thread raised goes to `errors`."""
    node = Node(f'churn_{time.monotonic_ns()}', context=ctx, enable_rosout=False)
    got = threading.Event()
    sub: Any = None

    def on_msg(msg: Any) -> None:
        got.set()
        if way == 'in_callback' and sub is not None:
            node.destroy_subscription(sub)

    sub = node.create_subscription(String, 'churn', on_msg, 10)
    executor: Any = (
        MultiThreadedExecutor(num_threads=2, context=ctx)
        if way == 'multi'
        else SingleThreadedExecutor(context=ctx)
    )
    executor.add_node(node)
    stop = threading.Event()

    def spin() -> None:
        try:
            if way == 'spin_once':
                while not stop.is_set():
                    executor.spin_once(timeout_sec=0.01)
            else:
                executor.spin()
        except BaseException as e:
            errors.append(e)

    thread = threading.Thread(target=spin, daemon=True)
    thread.start()
    got.wait(5)  # (the round churns as well without a message; most get one)
    if way in ('destroy_sub', 'spin_once', 'multi'):
        node.destroy_subscription(sub)
    elif way == 'destroy_node':
        node.destroy_node()
    elif way == 'remove_node':
        executor.remove_node(node)
    stop.set()
    executor.shutdown()
    thread.join(10)
    assert not thread.is_alive()
    if way != 'destroy_node':
        node.destroy_node()


def test_create_spin_destroy_under_1khz_never_raises(ros_context: Any, talker: Any) -> None:
    """R5-L1: subscriptions and nodes created, spun and destroyed under 1 kHz traffic, every
    way at once; the kept channel's hand-back raised `release unlocked lock` in 11 of 300."""
    pub = talker.create_publisher(String, 'churn', 10)
    stop = threading.Event()

    def publish() -> None:  # about 1 kHz
        while not stop.wait(0.001):
            pub.publish(String(data='x'))

    publisher = threading.Thread(target=publish, daemon=True)
    publisher.start()
    errors: list[BaseException] = []
    try:
        for i in range(CHURN_ROUNDS):
            _churn_round(ros_context, _CHURN_WAYS[i % len(_CHURN_WAYS)], errors)
    finally:
        stop.set()
        publisher.join(5)
    assert errors == []
