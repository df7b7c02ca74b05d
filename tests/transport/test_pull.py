"""PulledSamples: the consumer pulls from Zenoh's channel itself, a doorbell thread waits while
it is empty; order, KEEP_LAST depth and attachment filtering hold across the hand-overs."""

from __future__ import annotations

import threading
import time
from typing import Any

from ros2lite.qos import HistoryPolicy, QoSProfile
from ros2lite.runtime.delivery import payloads
from ros2lite.transport.attachment import encode_attachment
from ros2lite.transport.pull import PulledSamples
from tests.spinning import wait_until

KEEP_ALL = QoSProfile(history=HistoryPolicy.KEEP_ALL)
ATTACHMENT = encode_attachment(1, 0, bytes(16))


def _source(ctx: Any, key: str, qos: QoSProfile) -> tuple[PulledSamples, threading.Event]:
    ready = threading.Event()
    return PulledSamples(ctx.session, key, qos, ready.set, name=key), ready


def _put(ctx: Any, key: str, texts: list[str], attachment: bytes | None = ATTACHMENT) -> None:
    for text in texts:
        ctx.session.put(key, text.encode(), attachment=attachment)


def test_order_holds_across_doorbell_and_pulls(ros_context: Any) -> None:
    key = f'pull_test/order/{time.monotonic_ns()}'
    src, ready = _source(ros_context, key, KEEP_ALL)
    sent = [str(i) for i in range(600)]
    got: list[str] = []

    def producer() -> None:  # bursts with pauses, so the channel runs dry in between
        for start in range(0, len(sent), 50):
            _put(ros_context, key, sent[start : start + 50])
            time.sleep(0.005)

    thread = threading.Thread(target=producer)
    thread.start()
    limits = [1, 7, 64, 512]
    deadline = time.monotonic() + 10
    try:
        while len(got) < len(sent) and time.monotonic() < deadline:
            batch = src.take(limits[len(got) % 4])
            if not batch and not src.ready:
                ready.wait(0.1)
                ready.clear()
            got += [p.decode() for p in payloads(batch)]
    finally:
        thread.join()
        src.undeclare()
    assert got == sent


def test_keep_last_hands_out_the_newest_depth(ros_context: Any) -> None:
    key = f'pull_test/depth/{time.monotonic_ns()}'
    src, _ = _source(ros_context, key, QoSProfile(depth=3))
    try:
        _put(ros_context, key, [str(i) for i in range(10)])
        wait_until(lambda: src.ready)
        assert [p.decode() for p in payloads(src.take(10))] == ['7', '8', '9']
        assert src.take(10) == []
    finally:
        src.undeclare()


def test_samples_taken_back_come_first_and_keep_last_keeps_only_what_fits(
    ros_context: Any,
) -> None:
    key = f'pull_test/back/{time.monotonic_ns()}'
    src, _ = _source(ros_context, key, KEEP_ALL)
    try:
        _put(ros_context, key, [str(i) for i in range(10)])
        wait_until(lambda: src.ready)
        batch = src.take(5)
        src.put_back(batch[2:])
        got: list[str] = []
        wait_until(lambda: got.extend(p.decode() for p in payloads(src.take(3))) or len(got) >= 8)
        assert got == [str(i) for i in range(2, 10)]
    finally:
        src.undeclare()
    key = f'pull_test/back_last/{time.monotonic_ns()}'
    src, _ = _source(ros_context, key, QoSProfile(depth=3))
    try:
        _put(ros_context, key, ['a', 'b', 'c'])
        wait_until(lambda: src.ready)
        taken = src.take(2)
        _put(ros_context, key, ['d', 'e'])
        wait_until(lambda: not src._armed)  # (white box) the doorbell handed 'd' over
        src.take(0)  # pull what came, handing nothing out
        src.put_back(taken)  # a, b: only one of them still fits behind c, d, e
        assert [p.decode() for p in payloads(src.take(10))] == ['c', 'd', 'e']
    finally:
        src.undeclare()


def test_samples_without_attachment_are_never_handed_out(ros_context: Any) -> None:
    key = f'pull_test/bare/{time.monotonic_ns()}'
    src, _ = _source(ros_context, key, KEEP_ALL)
    try:
        _put(ros_context, key, ['bare'], attachment=None)
        _put(ros_context, key, ['1', '2'])
        _put(ros_context, key, ['bare'], attachment=None)
        _put(ros_context, key, ['3'])
        wait_until(lambda: src.ready)
        got: list[str] = []
        wait_until(lambda: got.extend(p.decode() for p in payloads(src.take(64))) or len(got) >= 3)
        assert got == ['1', '2', '3']
        _put(ros_context, key, ['bare'], attachment=None)  # alone, at the doorbell: dropped
        time.sleep(0.2)
        assert not src.ready and src.take(1) == []
        _put(ros_context, key, ['4'])  # the one-sample path
        wait_until(lambda: src.ready)
        assert [p.decode() for p in payloads(src.take(1))] == ['4']
    finally:
        src.undeclare()


def test_undeclare_ends_the_doorbell_thread(ros_context: Any) -> None:
    src, _ = _source(ros_context, f'pull_test/end/{time.monotonic_ns()}', KEEP_ALL)
    thread = src._thread
    assert thread.is_alive()
    src.undeclare()
    thread.join(timeout=5)
    assert not thread.is_alive()


def test_the_channel_goes_back_once_however_threads_race(ros_context: Any) -> None:
    """R5-L1, replayed on the channel: the consumer gives back a channel it emptied while
    another thread undeclares it (a subscription destroyed while its executor delivers).
    Both wake the doorbell; the second wake raised `release unlocked lock` whenever the
    doorbell had not yet taken the first."""
    errors: list[BaseException] = []
    for i in range(300):
        key = f'pull_test/race/{time.monotonic_ns()}/{i}'
        src, ready = _source(ros_context, key, QoSProfile(depth=10))
        _put(ros_context, key, ['a'])
        assert ready.wait(5)
        assert src.take(1, rearm_later=True)  # emptied: the consumer owes the channel back
        start = threading.Barrier(2)

        def undeclare(src: PulledSamples = src, start: threading.Barrier = start) -> None:
            start.wait()
            src.undeclare()

        other = threading.Thread(target=undeclare)
        other.start()
        start.wait()
        try:
            src.rearm()
        except RuntimeError as e:
            errors.append(e)
        other.join(5)
    assert errors == []


def test_a_peers_samples_without_attachment_are_reported_and_ours_are_not(
    ros_context: Any,
) -> None:
    """An interrupt (put_local) is dropped unheard; any other sample without an attachment is
    no ROS message and is counted to `on_unattached` (a flood is reported, never silent)."""
    from ros2lite.transport.session import put_local

    key = f'pull_test/unattached/{time.monotonic_ns()}'
    heard: list[int] = []
    ready = threading.Event()
    # KEEP_ALL: a KEEP_LAST ring may lose a sample whose delivery is under way at the moment
    # the filter is put in front of it (Zenoh deletes a ring with its subscriber)
    src = PulledSamples(ros_context.session, key, KEEP_ALL, ready.set, on_unattached=heard.append)
    try:
        put_local(ros_context.session, key)
        _put(ros_context, key, ['x', 'y', ''], attachment=None)  # as a peer's would come
        _put(ros_context, key, ['real'])
        assert ready.wait(5)
        assert list(payloads(src.take(8))) == [b'real']
    finally:
        src.undeclare()
    assert sum(heard) == 3  # the three of the peer, not the interrupt


def test_only_a_keys_sole_subscriber_in_the_session_keeps_its_channel(ros_context: Any) -> None:
    """An interrupt reaches every subscriber of its key in the session, so a channel whose key
    has another local subscriber is never kept (a second subscription lost its newest sample
    at depth 1 to a stray interrupt)."""
    key = f'pull_test/sole/{time.monotonic_ns()}'
    asked: list[PulledSamples] = []

    def keeper(channel: PulledSamples) -> bool:
        asked.append(channel)
        return True

    ready = threading.Event()
    first = PulledSamples(ros_context.session, key, QoSProfile(depth=1), ready.set, keeper=keeper)
    second = PulledSamples(ros_context.session, key, QoSProfile(depth=1), lambda: None)
    try:
        _put(ros_context, key, ['a'])
        assert ready.wait(5)
        assert first.take(1)
        assert not first.kept and asked == []  # shared key: handed back, keeper not asked
        second.undeclare()
        ready.clear()
        _put(ros_context, key, ['b'])
        assert ready.wait(5)
        assert first.take(1)
        assert first.kept and asked == [first]  # alone now: kept
        first.release()
        assert not first.kept
    finally:
        first.undeclare()
