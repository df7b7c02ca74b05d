"""Transient-local publishers whose history keeps to the QoS and to a bound in bytes (R5-G4).

zenoh-ext's advanced publisher keeps its cache whatever the samples' age and size; here a
history is forgotten on time by one thread for the process, and forgotten when its bytes
would pass HISTORY_BYTES.
"""

from __future__ import annotations

import contextlib
import heapq
import threading
import time
from collections import deque
from collections.abc import Callable

import zenoh
import zenoh.ext

__all__ = ["HISTORY_BYTES", "HistoryBoundedPublisher"]

HISTORY_BYTES = 64 << 20
"""The most payload bytes one publisher's history keeps for late joiners (a /rosout of 16 MB
lines at depth 1000 would keep 16 GB); the newest sample is always kept, whatever its size."""


class HistoryBoundedPublisher:
    """A transient-local publisher whose history is forgotten once its lifespan has passed.

    zenoh-ext's advanced publisher keeps the last `depth` samples whatever their age (and
    serves hour-old /rosout lines to a late joiner). With a finite lifespan, once the newest
    kept sample is older than it, the advanced publisher is made anew, empty (its cache
    cannot drop samples one by one): a late joiner then gets no expired sample. While samples
    keep coming, the older ones stay until depth pushes them out. The same is done when the
    kept samples' bytes would pass `limit`: the history starts again from the new sample. One
    publisher at a time keeps the samples in order (a second, plain publisher for large
    samples, tried once, let a large sample overtake a small one).
    """

    def __init__(
        self,
        make: Callable[[], zenoh.ext.AdvancedPublisher],
        lifespan: float | None,
        depth: int = 1,
        limit: int | None = None,
    ) -> None:
        self._make, self._lifespan = make, lifespan
        self._limit = HISTORY_BYTES if limit is None else limit
        self._cached: zenoh.ext.AdvancedPublisher | None = make()
        self._lock = threading.Lock()
        self._newest = 0.0  # monotonic time of the newest kept sample (0: none kept)
        self._sizes: deque[int] = deque(maxlen=max(depth, 1))  # what the cache holds
        self._bytes = 0

    def _keep(self, size: int) -> None:
        """Count a sample into the history, starting it anew first if it would not fit
        beside the older ones that stay (none stay at depth 1: nothing to start anew)."""
        full = len(self._sizes) == self._sizes.maxlen
        pushed_out = self._sizes[0] if full else 0
        staying = self._bytes - pushed_out
        if staying and staying + size > self._limit:
            with contextlib.suppress(Exception):  # the session is closed
                if self._cached is not None:
                    self._cached.undeclare()
            self._cached = self._make()
            self._sizes.clear()
            self._bytes = pushed_out = 0
        self._bytes += size - pushed_out
        self._sizes.append(size)

    def put(self, payload: bytes | zenoh.ZBytes, *, attachment: bytes | None = None) -> None:
        """Publish, keeping the sample for late joiners."""
        with self._lock:
            if self._cached is None:
                raise zenoh.ZError("the publisher is undeclared")
            self._keep(len(payload))
            self._cached.put(payload, attachment=attachment)
            if self._lifespan is not None:
                first = not self._newest
                self._newest = time.monotonic()
                if first:
                    _expiry.watch(self, self._newest + self._lifespan)

    def expire(self) -> float | None:
        """Forget the history if its newest sample has expired; else when to look again."""
        with self._lock:
            assert self._lifespan is not None
            due = self._newest + self._lifespan
            if self._cached is None or not self._newest:
                return None
            if time.monotonic() < due:
                return due
            with contextlib.suppress(Exception):  # the session is closed
                self._cached.undeclare()
            self._cached = None  # a put meanwhile waits for the lock, then goes to the new one
            self._cached = self._make()
            self._newest = 0.0
            self._sizes.clear()
            self._bytes = 0
            return None

    def undeclare(self) -> None:
        """Undeclare the publisher (its history goes with it)."""
        with self._lock:
            cached, self._cached = self._cached, None
        if cached is not None:
            with contextlib.suppress(Exception):  # the session is closed
                cached.undeclare()


class _Expiry:
    """One thread for the process, forgetting expired transient-local histories on time."""

    def __init__(self) -> None:
        self._due: list[tuple[float, int, HistoryBoundedPublisher]] = []
        self._cond = threading.Condition()
        self._thread: threading.Thread | None = None
        self._ids = iter(range(1 << 62))

    def watch(self, publisher: HistoryBoundedPublisher, due: float) -> None:
        with self._cond:
            heapq.heappush(self._due, (due, next(self._ids), publisher))
            if self._thread is None:
                self._thread = threading.Thread(target=self._run, name="tl-expiry", daemon=True)
                self._thread.start()
            self._cond.notify()

    def _run(self) -> None:
        while True:
            with self._cond:
                while not self._due or self._due[0][0] > time.monotonic():
                    self._cond.wait(self._due[0][0] - time.monotonic() if self._due else None)
                _, _, publisher = heapq.heappop(self._due)
            try:
                again = publisher.expire()
            except zenoh.ZError:
                again = None  # its session closed: nothing to keep or forget
            if again is not None:
                self.watch(publisher, again)


_expiry = _Expiry()
