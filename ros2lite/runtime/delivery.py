"""The hot loop of a busy typed subscription: one batch of samples to `callback(msg)`.

Per message it costs what cannot be avoided: the payload copied out of Zenoh, the generated
decoder, the user's callback and three cheap checks (destroyed, the awaited future, every
eighth message the batch deadline). Payload extraction and decoding run as C-level `map`s over
the batch; the Python loop only calls back. A sample that does not decode raises out of the
maps; the handler around the whole batch (free until something raises) tells such a bad
sample, which is dropped and reported, from an error of the callback, which propagates.
Samples of the batch that were not delivered go back to the front of the queue.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterator
from operator import attrgetter
from typing import TYPE_CHECKING, Protocol

from ros2lite.runtime.bad_samples import gid_of

if TYPE_CHECKING:
    from ros2lite.message_info import MessageInfo
    from ros2lite.transport.handles import Sample
    from ros2lite.transport.pull import PulledSamples

__all__ = ['BATCH', 'BATCH_TIME', 'deliver', 'deliver_with_info', 'payloads']

_payload_of = attrgetter('payload')


def payloads(samples: list[Sample]) -> Iterator[bytes]:
    """The CDR bytes of each sample, lazily and in order (each copied out once, when asked),
    through C-level maps: no Python frame per sample. The payload class's own `to_bytes`
    (half the cost of a method lookup per sample) comes from the first sample, so this
    module loads no zenoh."""
    if not samples:
        return iter(())
    to_bytes = type(samples[0].payload).to_bytes
    return map(to_bytes, map(_payload_of, samples))


# longest run of callbacks of one subscription in one executor turn: count and seconds
BATCH = 512
BATCH_TIME = 0.002


class _Target(Protocol):
    """What `deliver` needs of a subscription (ros2lite.subscription.Subscription): read per
    message, so plain attributes, not properties."""

    callback: Callable[..., object]
    destroyed: bool


BadSample = Callable[[bytes, bytes, Exception], None]
"""`(data, gid, error)`: drop and report a sample that does not decode."""


def deliver(
    sub: _Target,
    source: PulledSamples,
    decode: Callable[[bytes], object],
    limit: int,
    stop: Callable[[], bool] | None,
    bad_sample: BadSample,
) -> None:
    """Deliver up to `limit` samples of `source` to `sub.callback`, decoded by `decode`;
    stop early when `stop()` holds, the subscription is destroyed, or (for batches) after
    BATCH_TIME, so slow callbacks can't starve timers."""
    batch = source.take(limit, rearm_later=True)
    try:
        _deliver(sub, source, batch, decode, stop, bad_sample)
    finally:
        source.rearm()


def _deliver(
    sub: _Target,
    source: PulledSamples,
    batch: list[Sample],
    decode: Callable[[bytes], object],
    stop: Callable[[], bool] | None,
    bad_sample: BadSample,
) -> None:
    if len(batch) == 1:  # spin_once: one message, without the batch machinery
        sample = batch[0]
        data = sample.payload.to_bytes()
        try:
            msg = decode(data)
        except ValueError as e:  # a CdrError: dropped and reported
            bad_sample(data, gid_of(sample.attachment.to_bytes()), e)  # type: ignore[union-attr]
            return
        sub.callback(msg)
        return
    if not batch:
        return
    callback = sub.callback
    perf_counter = time.perf_counter
    deadline = perf_counter() + BATCH_TIME
    start = 0
    while True:
        i = start
        try:
            for msg in map(decode, payloads(batch if start == 0 else batch[start:])):
                callback(msg)
                i += 1
                if (
                    sub.destroyed
                    or (stop is not None and stop())
                    or (i & 7 == 7 and perf_counter() > deadline)
                ):
                    break
            else:
                return  # the whole batch went out
        except ValueError as e:  # a CdrError (imported lazily: tools stay light)?
            sample = batch[i]
            data = sample.payload.to_bytes()
            try:
                decode(data)
            except ValueError:
                attachment = sample.attachment
                bad_sample(data, gid_of(attachment.to_bytes() if attachment else None), e)
                start = i + 1  # dropped: go on with the rest
                continue
            source.put_back(batch[i + 1 :])
            raise  # it decodes: the error is the callback's
        except BaseException:
            source.put_back(batch[i + 1 :])
            raise
        if not sub.destroyed:
            source.put_back(batch[i:])  # stopped early: the rest waits for the next turn
        return


def deliver_with_info(
    sub: _Target,
    source: PulledSamples,
    decode: Callable[[bytes], object],
    limit: int,
    stop: Callable[[], bool] | None,
    deadline: float,
    bad_sample: BadSample,
    info: Callable[[bytes, int], MessageInfo],
) -> None:
    """`callback(msg, MessageInfo)` for up to `limit` samples: the slower loop, the info
    stamped with the time each sample is taken (as rclpy's take does). Stops early as
    `deliver` does (`deadline` 0 for single deliveries: never checked then)."""
    batch = source.take(limit, rearm_later=True)
    try:
        _deliver_with_info(sub, source, batch, decode, stop, deadline, bad_sample, info)
    finally:
        source.rearm()


def _deliver_with_info(
    sub: _Target,
    source: PulledSamples,
    batch: list[Sample],
    decode: Callable[[bytes], object],
    stop: Callable[[], bool] | None,
    deadline: float,
    bad_sample: BadSample,
    info: Callable[[bytes, int], MessageInfo],
) -> None:
    callback = sub.callback
    perf_counter = time.perf_counter
    for i, sample in enumerate(batch):
        if sub.destroyed:
            return
        if i & 7 == 7 and perf_counter() > deadline:
            source.put_back(batch[i:])
            return
        data = sample.payload.to_bytes()
        attachment = sample.attachment.to_bytes()  # type: ignore[union-attr]  # take() checked
        try:
            message = decode(data)
        except ValueError as e:  # a CdrError: dropped and reported
            bad_sample(data, gid_of(attachment), e)
            continue
        try:
            callback(message, info(attachment, time.time_ns()))
        except BaseException:
            source.put_back(batch[i + 1 :])
            raise
        if stop is not None and stop():
            source.put_back(batch[i + 1 :])
            return
