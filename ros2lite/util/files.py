"""Opening files for writing without trusting what is already on disk.

Bag folders, runtime directories and output paths may be shared with other users, or hold
leftovers of a crashed run: a symlink planted at a name we are about to write must never
redirect the write elsewhere. So every writer in ros2lite goes through here:

* :func:`create_new` makes a file that must not exist yet (``O_EXCL``: a symlink there, even a
  dangling one, is refused);
* :func:`replace_file` writes a whole file through a fresh, randomly named temporary file in
  the same directory and renames it over the target: a rename replaces a symlink itself,
  never its target, and a crash leaves either the old file or the new one;
* :func:`open_for_writing` truncates or appends to a file that may exist, refusing symlinks
  (``O_NOFOLLOW``);
* :func:`private_dir` checks that a per-user directory really is one (ours, not a symlink,
  closed to others) and falls back to ``~/.cache/ros2lite`` when it is not.
"""

from __future__ import annotations

import contextlib
import os
import stat
from pathlib import Path

from ros2lite.exceptions import Ros2liteError

__all__ = [
    'TEXT_LIMIT',
    'ReadRefused',
    'UnsafePathError',
    'create_new',
    'fallback_dir',
    'open_for_writing',
    'private_dir',
    'read_bounded',
    'read_text_bounded',
    'replace_file',
]

NOFOLLOW = getattr(os, 'O_NOFOLLOW', 0)
CLOEXEC = getattr(os, 'O_CLOEXEC', 0)


class UnsafePathError(Ros2liteError, OSError):
    """A path we were to write is a symlink, or a directory others control."""


def _refusal(path: str | os.PathLike[str], e: OSError) -> OSError:
    """The error for a failed open: a clear one when a symlink was in the way."""
    with contextlib.suppress(OSError):
        if os.path.islink(path):
            return UnsafePathError(f"refusing to write '{os.fspath(path)}': it is a symlink")
    return e


def create_new(path: str | os.PathLike[str], mode: int = 0o644) -> int:
    """A write-only descriptor of a new file; raises if anything (a symlink too) is there."""
    try:
        return os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | NOFOLLOW | CLOEXEC, mode)
    except OSError as e:
        raise _refusal(path, e) from None


def open_for_writing(path: str | os.PathLike[str], mode: int = 0o644, append: bool = False) -> int:
    """A write-only descriptor of `path`, created if need be and truncated unless `append`;
    a symlink at `path` is refused, not followed."""
    flags = os.O_WRONLY | os.O_CREAT | NOFOLLOW | CLOEXEC
    flags |= os.O_APPEND if append else os.O_TRUNC
    try:
        fd = os.open(path, flags, mode)
    except OSError as e:
        raise _refusal(path, e) from None
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        raise UnsafePathError(f"refusing to write '{os.fspath(path)}': not a regular file")
    return fd


def replace_file(
    path: str | os.PathLike[str], data: bytes | str, mode: int = 0o644, sync: bool = True
) -> None:
    """Write `data` as the whole new content of `path`, atomically (see the module doc)."""
    target = Path(path)
    blob = data.encode('utf-8') if isinstance(data, str) else data
    fd, tmp = temp_beside(target)
    try:
        os.fchmod(fd, mode)
        view = memoryview(blob)
        while view:
            view = view[os.write(fd, view) :]
        if sync:
            os.fsync(fd)
    except BaseException:
        os.close(fd)
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    os.close(fd)
    try:
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def temp_beside(path: str | os.PathLike[str], suffix: str = '.tmp') -> tuple[int, str]:
    """A new, randomly named file next to `path` (a name nobody could have planted)."""
    target = Path(path)
    import tempfile  # (on first write: finding the runtime dir is on every CLI call's path)

    return tempfile.mkstemp(prefix=f'.{target.name}.', suffix=suffix, dir=target.parent)


def _is_private(path: Path, uid: int) -> bool:
    try:
        st = os.lstat(path)
    except OSError:
        return False
    return stat.S_ISDIR(st.st_mode) and st.st_uid == uid and not st.st_mode & 0o077


def _usable_base(path: Path, uid: int) -> bool:
    """A base directory we may make our folder in: a real directory of ours that nobody
    else can write (a shared, world-writable XDG_RUNTIME_DIR is not)."""
    try:
        st = os.stat(path)
    except OSError:
        return False
    return stat.S_ISDIR(st.st_mode) and st.st_uid == uid and not st.st_mode & 0o022


def fallback_dir() -> Path:
    """``~/.cache/ros2lite``: where per-user files go when the runtime dir is not safe."""
    return Path.home() / '.cache' / 'ros2lite'


def _make_private(path: Path, uid: int) -> bool:
    try:
        path.mkdir(mode=0o700, parents=True)
    except FileExistsError:
        pass
    except OSError:  # no usable home (missing, not ours, not a directory): not private
        return False
    try:
        st = os.lstat(path)
    except OSError:
        return False
    if stat.S_ISDIR(st.st_mode) and st.st_uid == uid and st.st_mode & 0o077:
        with contextlib.suppress(OSError):
            os.chmod(path, 0o700)  # ours, just too open: close it
    return _is_private(path, uid)


def private_dir(base: str | os.PathLike[str] | None, name: str = 'ros2lite') -> Path:
    """``base/name`` when `base` is ours and closed to others and ``base/name`` is a private
    directory of ours (made 0700 if missing), else :func:`fallback_dir` under the same checks.

    Raises UnsafePathError when neither is safe (someone else owns the fallback, say)."""
    uid = os.getuid()
    if base:
        candidate = Path(base) / name
        if _usable_base(Path(base), uid) and _make_private(candidate, uid):
            return candidate
    fallback = fallback_dir()
    if _make_private(fallback, uid):
        return fallback
    if not os.path.lexists(fallback):
        raise UnsafePathError(
            f"no place for ros2lite's files: '{fallback}' cannot be created (no usable home "
            'directory); set HOME or XDG_RUNTIME_DIR to a directory of this user'
        )
    raise UnsafePathError(
        f"no safe directory for ros2lite's files: '{fallback}' is not a private directory "
        'of this user (check its owner and mode, or remove it)'
    )


def read_bounded(path: Path, limit: int, error: type[Exception], what: str) -> bytes:
    """The bytes of a file we parse whole (a manifest, a launch file, a parameters file): a
    read error, anything but a regular file (a FIFO would block, `/dev/zero` never ends) or
    a file over `limit` bytes becomes one `error` naming the path (`what` says what the file
    should have been)."""
    try:
        # O_NONBLOCK: opening a FIFO must not wait for a writer before we can refuse it
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError as e:
        raise error(f'{path}: {e.strerror or e}') from None
    try:
        regular = stat.S_ISREG(os.fstat(fd).st_mode)
        if regular:
            with os.fdopen(fd, 'rb') as f:
                fd = -1
                # no more than one byte past the limit is read
                data = f.read(limit + 1)
    except OSError as e:
        raise error(f'{path}: {e.strerror or e}') from None
    finally:
        if fd >= 0:
            os.close(fd)
    if not regular:
        raise error(f'{path}: not a regular file, so not read as {what}')
    if len(data) > limit:
        raise error(f'{path}: too large for {what}')
    return data


class ReadRefused(Ros2liteError, OSError):
    """A file not read (see :func:`read_text_bounded`); ``reason`` says why without the
    path, for callers that word their own line."""

    def __init__(self, message: str) -> None:
        super().__init__(message)
        self.reason = message.partition(': ')[2] or message


def read_text_bounded(
    path: str | os.PathLike[str], what: str, limit: int = 0, error: type[Exception] = ReadRefused
) -> str:
    """:func:`read_bounded` as UTF-8 text (`limit` 0: :data:`TEXT_LIMIT`); undecodable
    bytes are the same one `error`."""
    path = Path(path)
    data = read_bounded(path, limit or TEXT_LIMIT, error, what)
    try:
        return data.decode('utf-8')
    except UnicodeDecodeError as e:
        raise error(f'{path}: not UTF-8 text ({e.reason} at byte {e.start})') from None


# what a file a user hands us may hold: YAML of parameters, QoS, bag metadata, a launch file
TEXT_LIMIT = 64 * 1024 * 1024
