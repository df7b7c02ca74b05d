"""The one place that turns a subscription's receiving strategy into a receiver: typed pull
(:class:`~ros2lite.transport.pull.PulledSamples`), raw queue or arrival hook
(:class:`~ros2lite.transport.session.SampleReceiver`)."""

from __future__ import annotations

from collections import deque
from collections.abc import Callable

from ros2lite.qos import QoSProfile
from ros2lite.transport.handles import Receiving, Sample, Session
from ros2lite.transport.pull import PulledSamples
from ros2lite.transport.session import SampleReceiver

__all__ = ['Receiving', 'open_receiver']


def open_receiver(
    receiving: Receiving,
    session: Session,
    key: str,
    qos: QoSProfile,
    on_ready: Callable[[], None],
    *,
    buffer: deque[tuple[Sample, int]] | None = None,
    hook: Callable[[Sample], None] | None = None,
    name: str = '',
    keeper: Callable[[PulledSamples], bool] | None = None,
    on_unattached: Callable[[int], None] | None = None,
) -> PulledSamples | SampleReceiver:
    """Declare a subscriber on `key` that receives the `receiving` way. `on_ready()` (any
    thread) says samples wait: typed pull takes nothing else; raw queue fills `buffer` with
    `(sample, arrival ns)`; arrival hook calls `hook(sample)` on the receive thread and
    fills nothing (the hook calls on_ready itself if it queues anything). `keeper` (typed
    pull only) may keep an emptied channel for its consumer to wait in; `on_unattached(n)`
    (typed pull and raw queue) hears of samples without an attachment that were not this
    process's interrupts."""
    if (buffer is not None) != (receiving is Receiving.RAW_QUEUE):
        raise ValueError('a buffer goes with the raw queue, and only with it')
    if (hook is not None) != (receiving is Receiving.ARRIVAL_HOOK):
        raise ValueError('a hook goes with the arrival hook, and only with it')
    if receiving is Receiving.TYPED_PULL:
        return PulledSamples(
            session, key, qos, on_ready, name=name, keeper=keeper, on_unattached=on_unattached
        )
    if receiving is Receiving.RAW_QUEUE:
        assert buffer is not None
        return SampleReceiver(
            session, key, qos, buffer, on_ready, name=name, on_unattached=on_unattached
        )
    assert hook is not None
    return SampleReceiver(session, key, qos, deque(maxlen=0), on_ready, hook=hook, name=name)
