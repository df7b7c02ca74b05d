"""Large messages without a page fault per buffer: glibc's allocator thresholds for a node.

Every large message makes a few buffers of its size (the CDR bytes, Zenoh's copy, the decoded
array). glibc serves an allocation above its mmap threshold (128 KiB, raised at run time only
to the size of the last freed block, which a same-sized next message does not exceed) with a
fresh mmap, and unmaps it on free, so each 1 MiB buffer costs 256 page faults: measured here,
publishing a 1 MiB image took 1.5 ms instead of 75 µs. A node therefore raises the mmap
threshold to glibc's maximum (32 MiB) and the trim threshold above it, so freed buffers are
reused from the heap instead. The price would be freed memory kept mapped: a listener held
300 MB after eight 16 MB samples (in the arenas of several threads, which trim little of
their own). So a watcher thread gives it back: every RELEASE_PERIOD it asks glibc how much
freed memory it holds, and above RELEASE_ABOVE returns it to the system (malloc_trim), at
most once a period: buffers of a steady stream of large messages are still reused in
between, and a burst of large samples no longer stays in the process.

Nothing happens off glibc, or when the environment already tunes malloc (`MALLOC_*_`
variables, `GLIBC_TUNABLES`), or with `ROS2LITE_MALLOC_TUNING=0`.
"""

from __future__ import annotations

import os
import sys
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import ctypes

__all__ = [
    'MMAP_THRESHOLD',
    'RELEASE_ABOVE',
    'RELEASE_PERIOD',
    'TRIM_THRESHOLD',
    'keep_large_buffers',
]

MMAP_THRESHOLD = 32 * 1024 * 1024  # glibc's upper limit on 64-bit
TRIM_THRESHOLD = 128 * 1024 * 1024
RELEASE_ABOVE = 32 * 1024 * 1024  # freed bytes the allocator may keep between two looks
RELEASE_PERIOD = 2.0  # seconds between two looks
_M_TRIM_THRESHOLD = -1  # mallopt parameter numbers (malloc.h)
_M_MMAP_THRESHOLD = -3
_USER_TUNING = ('MALLOC_MMAP_THRESHOLD_', 'MALLOC_TRIM_THRESHOLD_', 'GLIBC_TUNABLES')

_tuned: bool | None = None


def keep_large_buffers() -> bool:
    """Tune this process' allocator for large messages (once); True when it is tuned."""
    global _tuned
    if _tuned is None:
        _tuned = _tune()
    return _tuned


def _tune() -> bool:
    env = os.environ
    if not sys.platform.startswith('linux') or env.get('ROS2LITE_MALLOC_TUNING') == '0':
        return False
    if any(name in env for name in _USER_TUNING):
        return False  # the user's own settings win
    import ctypes

    try:
        libc = ctypes.CDLL(None)
        libc.gnu_get_libc_version  # noqa: B018  # glibc, not musl: mallopt means the same
        mallopt = libc.mallopt
    except (OSError, AttributeError):
        return False
    mallopt.argtypes = (ctypes.c_int, ctypes.c_int)
    mallopt.restype = ctypes.c_int
    tuned = bool(
        mallopt(_M_MMAP_THRESHOLD, MMAP_THRESHOLD) and mallopt(_M_TRIM_THRESHOLD, TRIM_THRESHOLD)
    )
    if tuned:
        _start_release(libc)
    return tuned


def _start_release(libc: ctypes.CDLL) -> None:
    """The watcher thread that returns freed memory above RELEASE_ABOVE (see the module doc);
    glibc 2.33+ (mallinfo2), else nothing."""
    import ctypes
    import threading

    class _Info(ctypes.Structure):
        _fields_ = [
            (name, ctypes.c_size_t)
            for name in (
                'arena', 'ordblks', 'smblks', 'hblks', 'hblkhd', 'usmblks', 'fsmblks',
                'uordblks', 'fordblks', 'keepcost',
            )
        ]  # fmt: skip

    try:
        mallinfo2 = libc.mallinfo2
        malloc_trim = libc.malloc_trim
    except AttributeError:
        return
    mallinfo2.restype = _Info
    malloc_trim.argtypes = (ctypes.c_size_t,)
    malloc_trim.restype = ctypes.c_int

    never = threading.Event()  # a sleep the interpreter's exit does not wait for

    def watch() -> None:
        while not never.wait(RELEASE_PERIOD):
            if mallinfo2().fordblks > RELEASE_ABOVE:
                malloc_trim(0)

    threading.Thread(target=watch, name='ros2lite-memory', daemon=True).start()
