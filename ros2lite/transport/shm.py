"""Zenoh shared memory as rmw_zenoh uses it: switched on by the session config key
``transport/shared_memory/enabled`` (both rmw_zenoh's default configs and ours say false),
sized by ``ZENOH_SHM_ALLOC_SIZE`` and used for payloads of at least
``ZENOH_SHM_MESSAGE_SIZE_THRESHOLD`` bytes (a power of two).

A session's provider is one fixed pool, so what a slow subscriber can pin is bounded by
``alloc_size``: when the pool is full (after a garbage collection) the payload goes as plain
bytes, as rmw_zenoh falls back. Zenoh itself hands the bytes to peers that cannot map the
segment (another host, or shared memory off on their side).

Lifetimes: zenoh-python 1.10's ``ZShm``/``ZShmMut`` expose no buffer protocol, so a
received payload is copied once out of the segment by ``to_bytes()`` (a memcpy, no socket),
and the sender's chunk returns to its pool as soon as every receiver drops its sample.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable, Mapping
from dataclasses import dataclass

import zenoh

__all__ = [
    "DEFAULT_ALLOC_SIZE",
    "DEFAULT_THRESHOLD",
    "ShmPublisher",
    "ShmSettings",
    "forget",
    "register",
    "settings_of",
    "shm_settings",
]

ALLOC_ENV = "ZENOH_SHM_ALLOC_SIZE"
THRESHOLD_ENV = "ZENOH_SHM_MESSAGE_SIZE_THRESHOLD"
# rmw_zenoh's defaults since Jazzy 0.2.8, Kilted 0.6.5 and Rolling 0.10.0 (48 MiB pool);
# its threshold default is 512 bytes on every distro with shared memory
DEFAULT_ALLOC_SIZE = 48 * 1024 * 1024
DEFAULT_THRESHOLD = 512
# Humble's rmw_zenoh (0.1.x) has no shared-memory publishing
_WITHOUT_SHM = frozenset({"humble"})


@dataclass(frozen=True)
class ShmSettings:
    """Whether a session publishes through shared memory, its pool size, its threshold."""

    enabled: bool
    alloc_size: int = DEFAULT_ALLOC_SIZE
    threshold: int = DEFAULT_THRESHOLD


def _positive(text: str | None) -> int | None:
    try:
        value = int(text) if text else 0
    except ValueError:
        return None
    return value if value > 0 else None


def shm_settings(config: zenoh.Config, env: Mapping[str, str] | None = None) -> ShmSettings:
    """The settings rmw_zenoh derives: the config key (after ``ZENOH_CONFIG_OVERRIDE``), then
    the two variables; a threshold that is not a power of two keeps the default."""
    environ = os.environ if env is None else env
    if environ.get("ROS_DISTRO", "").lower() in _WITHOUT_SHM:
        return ShmSettings(False)
    try:
        enabled = config.get_json("transport/shared_memory/enabled").strip() == "true"
    except zenoh.ZError:
        enabled = False
    alloc = _positive(environ.get(ALLOC_ENV)) or DEFAULT_ALLOC_SIZE
    threshold = _positive(environ.get(THRESHOLD_ENV))
    if threshold is None or threshold & (threshold - 1):
        threshold = DEFAULT_THRESHOLD
    return ShmSettings(enabled, alloc, threshold)


# per open session (zenoh's Session takes no weak reference): its settings and its provider
_settings: dict[int, ShmSettings] = {}
_providers: dict[int, _Pool] = {}
_lock = threading.Lock()


class _Pool:
    """A session's provider, made on the first large payload (a pool costs /dev/shm space)."""

    def __init__(self, size: int) -> None:
        self._size = size
        self._provider: zenoh.shm.ShmProvider | None = None
        self._lock = threading.Lock()

    def payload(self, data: bytes | bytearray | memoryview) -> zenoh.ZBytes | bytes:
        """`data` in a chunk of the pool, or `data` itself when the pool has no room."""
        with self._lock:
            if self._provider is None:
                self._provider = zenoh.shm.ShmProvider.default_backend(self._size)
            try:
                chunk = self._provider.alloc(len(data), zenoh.shm.GarbageCollect())
            except zenoh.ZError:
                return bytes(data)
        # a chunk takes bytes or bytearray only, not a memoryview
        chunk[:] = data if isinstance(data, (bytes, bytearray)) else bytes(data)
        return zenoh.ZBytes(chunk)


def register(session: object, settings: ShmSettings) -> None:
    """Remember an opened session's settings (its publishers read them when declared)."""
    with _lock:
        if not settings.enabled:  # a closed session's id may come back: clear it
            _settings.pop(id(session), None)
            _providers.pop(id(session), None)
            return
        _settings[id(session)] = settings
        _providers[id(session)] = _Pool(settings.alloc_size)


def forget(session: object) -> None:
    """Drop a closing session's settings and pool."""
    with _lock:
        _settings.pop(id(session), None)
        _providers.pop(id(session), None)


def settings_of(session: object) -> ShmSettings:
    """The settings registered for `session` (off when none were)."""
    return _settings.get(id(session), ShmSettings(False))


class ShmPublisher:
    """A publisher whose payloads of at least the threshold go through the session's pool."""

    def __init__(
        self,
        inner: Callable[..., object],
        undeclare: Callable[[], object],
        pool: _Pool,
        threshold: int,
    ) -> None:
        self._inner = inner
        self._undeclare = undeclare
        self._pool = pool
        self._threshold = threshold

    def put(
        self, payload: bytes | bytearray | memoryview, *, attachment: bytes | None = None
    ) -> None:
        """Send `payload`, from shared memory when it is large enough and the pool has room."""
        if len(payload) >= self._threshold:
            self._inner(self._pool.payload(payload), attachment=attachment)
        else:
            self._inner(payload, attachment=attachment)

    def undeclare(self) -> None:
        """Undeclare the publisher beneath."""
        self._undeclare()


def shm_publisher(
    session: object, put: Callable[..., object], undeclare: Callable[[], object]
) -> ShmPublisher | None:
    """A shared-memory publisher over `put` when `session` has shared memory on, else None."""
    settings = _settings.get(id(session))
    pool = _providers.get(id(session))
    if settings is None or pool is None:
        return None
    return ShmPublisher(put, undeclare, pool, settings.threshold)
