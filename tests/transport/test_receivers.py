"""The receiver factory without a router: one lone Zenoh session (no listen, no connect, no
scouting) delivers its own puts, so each strategy is seen doing its job."""

from __future__ import annotations

import threading
import time
from collections import deque
from collections.abc import Iterator
from typing import Any

import pytest

from ros2lite.qos import QoSProfile
from ros2lite.transport.attachment import encode_attachment
from ros2lite.transport.pull import PulledSamples
from ros2lite.transport.receivers import Receiving, open_receiver
from ros2lite.transport.session import SampleReceiver
from tests.spinning import wait_until

ATTACHMENT = encode_attachment(1, 0, bytes(16))
QOS = QoSProfile(depth=10)


@pytest.fixture(scope='module')
def lone_session() -> Iterator[Any]:
    import zenoh

    config = zenoh.Config()
    for key, value in (
        ('mode', '"peer"'),
        ('listen/endpoints', '[]'),
        ('connect/endpoints', '[]'),
        ('scouting/multicast/enabled', 'false'),
    ):
        config.insert_json5(key, value)
    session = zenoh.open(config)
    yield session
    session.close()


def _key(name: str) -> str:
    return f'receivers_test/{name}/{time.monotonic_ns()}'


def test_typed_pull_leaves_samples_in_the_channel_for_the_consumer(lone_session: Any) -> None:
    key = _key('pull')
    ready = threading.Event()
    receiver = open_receiver(Receiving.TYPED_PULL, lone_session, key, QOS, ready.set, name=key)
    try:
        assert isinstance(receiver, PulledSamples)
        lone_session.put(key, b'one', attachment=ATTACHMENT)
        assert ready.wait(10)
        wait_until(lambda: receiver.ready, 10)
        assert [s.payload.to_bytes() for s in receiver.take(10)] == [b'one']
    finally:
        receiver.undeclare()


def test_raw_queue_fills_the_buffer_with_arrival_times(lone_session: Any) -> None:
    key = _key('raw')
    buffer: deque[Any] = deque(maxlen=10)
    ready = threading.Event()
    before = time.time_ns()
    receiver = open_receiver(
        Receiving.RAW_QUEUE, lone_session, key, QOS, ready.set, buffer=buffer, name=key
    )
    try:
        assert isinstance(receiver, SampleReceiver)
        lone_session.put(key, b'two', attachment=ATTACHMENT)
        assert ready.wait(10)
        sample, received = buffer.popleft()
        assert sample.payload.to_bytes() == b'two' and received >= before
    finally:
        receiver.undeclare()


def test_arrival_hook_sees_every_sample_on_the_receive_thread(lone_session: Any) -> None:
    key = _key('hook')
    seen: list[tuple[bytes, str]] = []
    ready = threading.Event()

    def hook(sample: Any) -> None:
        seen.append((sample.payload.to_bytes(), threading.current_thread().name))

    receiver = open_receiver(
        Receiving.ARRIVAL_HOOK, lone_session, key, QOS, ready.set, hook=hook, name=key
    )
    try:
        for i in range(3):
            lone_session.put(key, f'{i}'.encode(), attachment=ATTACHMENT)
        wait_until(lambda: len(seen) == 3, 10)
        assert [data for data, _ in seen] == [b'0', b'1', b'2']
        assert all(name != threading.current_thread().name for _, name in seen)
        assert not ready.is_set()  # the hook consumed them: nothing queued
    finally:
        receiver.undeclare()


@pytest.mark.parametrize(
    ('receiving', 'kwargs'),
    [
        (Receiving.TYPED_PULL, {'buffer': deque()}),
        (Receiving.TYPED_PULL, {'hook': print}),
        (Receiving.RAW_QUEUE, {}),
        (Receiving.RAW_QUEUE, {'buffer': deque(), 'hook': print}),
        (Receiving.ARRIVAL_HOOK, {}),
    ],
)
def test_a_strategy_takes_only_its_own_parts(
    lone_session: Any, receiving: Receiving, kwargs: dict[str, Any]
) -> None:
    with pytest.raises(ValueError):
        open_receiver(receiving, lone_session, _key('bad'), QOS, lambda: None, **kwargs)
