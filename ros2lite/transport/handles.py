"""What the rest of the library holds of Zenoh, described without importing it.

The library outside :mod:`ros2lite.transport` keeps a session, declared entities and received
samples only to hand them back to this package (or to close and undeclare them), so these
protocols say exactly that much. A ``zenoh.Session`` satisfies :class:`Session`; the functions
of :mod:`ros2lite.transport.session` take a :class:`Session` and narrow it to the zenoh type
at the seam, so the zenoh object never crosses it untyped.
"""

from __future__ import annotations

import enum
from collections.abc import Sequence
from typing import Protocol

__all__ = ['Handle', 'Payload', 'Receiving', 'Sample', 'Session', 'SessionInfo']


class SessionInfo(Protocol):
    """Who the session is and which routers it reaches (``zenoh.SessionInfo``)."""

    def zid(self) -> object:
        """The session's Zenoh id (its ``str()`` is the hex text in liveliness tokens)."""
        ...

    def routers_zid(self) -> Sequence[object]:
        """Ids of the routers the session is connected to (empty: none)."""
        ...


class Session(Protocol):
    """An open Zenoh session, as the library outside the transport package uses it."""

    @property
    def info(self) -> SessionInfo:
        """Identity and connectivity of the session."""
        ...

    def zid(self) -> object:
        """The session's Zenoh id."""
        ...

    def close(self) -> object:
        """Close the session; every entity declared on it goes too."""
        ...


class Handle(Protocol):
    """Something declared on a session (token, publisher, subscriber, queryable, querier)."""

    def undeclare(self) -> None:
        """Withdraw it from the session."""
        ...


class Payload(Protocol):
    """Received bytes still held by Zenoh (``zenoh.ZBytes``): copied out on demand."""

    def to_bytes(self) -> bytes:
        """The bytes, copied into Python."""
        ...

    def __len__(self) -> int:
        """How many bytes (without copying them)."""
        ...


class Sample(Protocol):
    """What a received sample offers (``zenoh.Sample``): its payload and attachment."""

    @property
    def payload(self) -> Payload:
        """The CDR bytes."""
        ...

    @property
    def attachment(self) -> Payload | None:
        """The rmw_zenoh attachment (sequence number, timestamp, GID), if any."""
        ...


class Receiving(enum.Enum):
    """How a subscription receives its samples (the strategies of
    :func:`ros2lite.transport.receivers.open_receiver`)."""

    # the executor thread pulls typed samples straight from Zenoh's channel; a doorbell
    # thread only waits while it is empty (ros2lite.transport.pull)
    TYPED_PULL = 'typed pull'
    # a pump thread moves raw samples, with their arrival times, into a bounded deque
    RAW_QUEUE = 'raw queue'
    # a tool's function sees every sample on the receive thread, at arrival
    ARRIVAL_HOOK = 'arrival hook'
