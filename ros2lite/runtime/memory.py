"""Large messages without a page fault per buffer: glibc's allocator thresholds for a node.

Every large message makes a few buffers of its size (the CDR bytes, Zenoh's copy, the decoded
array). glibc serves an allocation above its mmap threshold (128 KiB, raised at run time only
to the size of the last freed block, which a same-sized next message does not exceed) with a
fresh mmap, and unmaps it on free, so each 1 MiB buffer costs 256 page faults: measured here,
publishing a 1 MiB image took 1.5 ms instead of 75 µs. A node therefore raises the mmap
threshold to glibc's maximum (32 MiB) and the trim threshold above it, so freed buffers are
reused from the heap instead. The price is that up to TRIM_THRESHOLD of freed memory may stay
mapped to the process.

Nothing happens off glibc, or when the environment already tunes malloc (`MALLOC_*_`
variables, `GLIBC_TUNABLES`), or with `ROS2LITE_MALLOC_TUNING=0`.
"""

from __future__ import annotations

import os
import sys

__all__ = ['MMAP_THRESHOLD', 'TRIM_THRESHOLD', 'keep_large_buffers']

MMAP_THRESHOLD = 32 * 1024 * 1024  # glibc's upper limit on 64-bit
TRIM_THRESHOLD = 128 * 1024 * 1024
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
    return bool(
        mallopt(_M_MMAP_THRESHOLD, MMAP_THRESHOLD) and mallopt(_M_TRIM_THRESHOLD, TRIM_THRESHOLD)
    )
