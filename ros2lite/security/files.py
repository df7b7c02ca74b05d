"""Writing keystore files without ever following a symlink, and reading XML safely.

A keystore lives in a directory other users may share; a planted symlink must not redirect
a private key or a signed document elsewhere.  Every write here opens with ``O_NOFOLLOW``
and every directory we write into is checked to be a real directory below the keystore.
The symlinks sros2's layout has (``identity_ca.cert.pem`` → ``ca.cert.pem`` …) are made by
us, never written through.  A private key is never written into a file that exists: it is
created afresh (``O_EXCL``, 0600) in a directory of ours, so a file or directory another user
planted there (to read the key, or swap it later) is refused.
"""

from __future__ import annotations

import contextlib
import os
import stat
import xml.etree.ElementTree as ET
from pathlib import Path

from ros2lite.security.errors import KeystoreError, PolicyError
from ros2lite.util.files import UnsafePathError, create_new, read_bounded

__all__ = ['make_dirs', 'parse_xml', 'read_bytes', 'symlink', 'write_file', 'write_private']

# Policies and permissions are small; anything bigger is not one.
MAX_XML_BYTES = 4 * 1024 * 1024


def make_dirs(root: Path, relative: Path | str = '.') -> Path:
    """Create ``root/relative`` (parents too) and check that no part of it is a symlink."""
    path = root
    parts = [p for p in Path(relative).parts if p not in ('.', '')]
    for part in ['', *parts]:
        path = path / part if part else path
        if path.is_symlink():
            raise KeystoreError(f"refusing to write below '{path}': it is a symlink")
        try:
            path.mkdir(mode=0o755, exist_ok=True)
        except FileExistsError:
            raise KeystoreError(f"'{path}' exists and is not a directory") from None
        except OSError as exc:
            raise KeystoreError(f"cannot create '{path}': {exc.strerror}") from None
        if not path.is_dir():
            raise KeystoreError(f"'{path}' exists and is not a directory")
    return path


def write_file(path: Path, data: bytes, mode: int = 0o644) -> None:
    """Replace ``path``'s content; a symlink there is refused, never followed."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_TRUNC | getattr(os, 'O_NOFOLLOW', 0)
    try:
        fd = os.open(path, flags, mode)
    except OSError as exc:
        if path.is_symlink():
            raise KeystoreError(f"refusing to write '{path}': it is a symlink") from None
        raise KeystoreError(f"cannot write '{path}': {exc.strerror}") from None
    try:
        os.fchmod(fd, mode)
        view = memoryview(data)
        while view:
            view = view[os.write(fd, view) :]
    finally:
        os.close(fd)


def write_private(path: Path, data: bytes) -> None:
    """Write a private key as a new file of ours, 0600; a stale one of ours is replaced, one
    another user owns (or a directory they own) is refused, a symlink is never followed."""
    uid = os.geteuid()
    what = f"refusing to write the private key '{path}'"
    existing: os.stat_result | None = None
    try:
        parent = os.stat(path.parent)
        with contextlib.suppress(FileNotFoundError):
            existing = os.lstat(path)
    except OSError as exc:
        raise KeystoreError(f"cannot write '{path}': {exc.strerror}") from None
    if parent.st_uid != uid:
        raise KeystoreError(f'{what}: its directory belongs to another user (uid {parent.st_uid})')
    if existing is not None:
        if stat.S_ISLNK(existing.st_mode):
            raise KeystoreError(f'{what}: it is a symlink')
        if existing.st_uid != uid:
            raise KeystoreError(
                f'{what}: it exists and belongs to another user (uid {existing.st_uid})'
            )
        path.unlink()
    try:
        fd = create_new(path, 0o600)
    except (UnsafePathError, OSError) as exc:
        raise KeystoreError(f'{what}: {exc}') from None
    try:
        view = memoryview(data)
        while view:
            view = view[os.write(fd, view) :]
    finally:
        os.close(fd)


def symlink(target: str, link: Path) -> None:
    """Make ``link`` point at ``target`` (relative), replacing what was there (sros2 does)."""
    if link.is_symlink() and os.readlink(link) == target:
        return
    if os.path.normpath(link.parent / target) == os.path.normpath(link):
        return  # the file itself (enclave '/' lives in the enclaves directory)
    if link.is_symlink() or link.exists():
        if link.is_dir() and not link.is_symlink():
            raise KeystoreError(f"'{link}' is a directory")
        link.unlink()
    try:
        os.symlink(target, link)
    except OSError as exc:
        raise KeystoreError(f"cannot create '{link}': {exc.strerror}") from None


def read_bytes(path: Path, what: str, limit: int = MAX_XML_BYTES) -> bytes:
    """A file's bytes, at most ``limit`` of them; errors (PolicyError) name the file."""
    return read_bounded(path, limit, PolicyError, f'{what} (at most {limit} bytes)')


def parse_xml(data: bytes, origin: str) -> ET.Element:
    """Parse an XML document that may come from anyone: no DTDs, hence no entities."""
    head = data[:4096].lower()
    if b'<!doctype' in head or b'<!entity' in data.lower():
        raise PolicyError(f'{origin}: DTDs and entities are not accepted')
    try:
        return ET.fromstring(data)
    except ET.ParseError as exc:
        raise PolicyError(f'{origin}: not well-formed XML ({exc})') from None
