"""Assets (the protocol's `fetchAsset`): a robot's meshes and textures by `package://` or
`file://` URI, so a URDF robot shows in Foxglove and Lichtblick.

Only files inside the share folder of a package the package index knows are served: the URI
is percent-decoded, a `..` segment refused, the path resolved (symlinks followed, then
checked again against the share folders), only a regular file, at most `MAX_ASSET_BYTES`.
Anything else of the filesystem is refused with one line, the protocol's error status.
"""

from __future__ import annotations

import os
import re
import stat
import threading
import time
from pathlib import Path
from urllib.parse import unquote

from ros2lite.bundled.foxglove_bridge.state import matches
from ros2lite.exceptions import Ros2liteError
from ros2lite.pkg.index import PackageIndex
from ros2lite.pkg.manifest import is_valid_package_name

__all__ = ['MAX_ASSET_BYTES', 'AssetError', 'PackageAssets']

# a mesh larger than this is refused (the client's WebSocket buffers the whole reply)
MAX_ASSET_BYTES = 64 * 1024 * 1024
# the package index is read again at most this often (seconds), when a lookup misses
_REREAD_PERIOD = 5.0


class AssetError(Ros2liteError, ValueError):
    """A URI the bridge will not serve; the message goes to the client as is."""


class PackageAssets:
    """Serves files of package share folders by URI (`fetch`, the SDK's asset handler)."""

    def __init__(self, allowlist: list[re.Pattern[str]], *, limit: int = MAX_ASSET_BYTES) -> None:
        self._allowlist = allowlist
        self._limit = limit
        self._lock = threading.Lock()
        self._index: PackageIndex | None = None
        self._read_at = 0.0
        self._roots: list[Path] | None = None

    def fetch(self, uri: str) -> bytes:
        """The bytes of the file `uri` names; AssetError (one line) when it is not served."""
        if len(uri) > 4096 or not matches(self._allowlist, uri):
            raise AssetError(f'Asset URI not allowed: {_shown(uri)}')
        path = self.resolve(uri)
        return self._read(path, uri)

    def resolve(self, uri: str) -> Path:
        """The file inside a package share folder that `uri` names (resolved)."""
        if uri.startswith('package://'):
            package, _, rest = unquote(uri[len('package://') :]).partition('/')
            if not is_valid_package_name(package):
                raise AssetError(f'Not a package name in {_shown(uri)}')
            share = self._share(package)
            if share is None:
                raise AssetError(f"Package '{package}' not found")
            _check_segments(rest, uri)
            roots = [share]
            target = share / rest
        elif uri.startswith('file://'):
            path = unquote(uri[len('file://') :])
            if not path.startswith('/'):
                raise AssetError(f'Only absolute file:// URIs are served: {_shown(uri)}')
            _check_segments(path, uri)
            roots = self._all_shares()
            target = Path(path)
        else:
            raise AssetError(f'Unsupported asset URI scheme: {_shown(uri)}')
        try:
            found = target.resolve(strict=True)
        except (OSError, RuntimeError):
            raise AssetError(f'Asset not found: {_shown(uri)}') from None
        if not any(found.is_relative_to(root) for root in roots):
            # a symlink (or a file:// path) leading out of every package's share folder
            raise AssetError(f'Asset outside the package share folders: {_shown(uri)}')
        return found

    def _read(self, path: Path, uri: str) -> bytes:
        try:
            # no FIFO or device blocks us; the last component is not swapped for a link
            fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOFOLLOW | os.O_CLOEXEC)
        except OSError as e:
            raise AssetError(f'Cannot read {_shown(uri)}: {e.strerror}') from None
        with os.fdopen(fd, 'rb') as f:
            info = os.fstat(f.fileno())
            if not stat.S_ISREG(info.st_mode):
                raise AssetError(f'Not a regular file: {_shown(uri)}')
            if info.st_size > self._limit:
                raise AssetError(
                    f'Asset too large ({info.st_size} bytes, at most {self._limit}): {_shown(uri)}'
                )
            data = f.read(self._limit + 1)
        if len(data) > self._limit:
            raise AssetError(f'Asset too large (at most {self._limit} bytes): {_shown(uri)}')
        return data

    # -- the package index ---------------------------------------------------------------------
    def _fresh_index(self, reread: bool) -> PackageIndex:
        with self._lock:
            now = time.monotonic()
            if self._index is None or (reread and now - self._read_at >= _REREAD_PERIOD):
                self._index, self._read_at, self._roots = PackageIndex(), now, None
            return self._index

    def _share(self, package: str) -> Path | None:
        for reread in (False, True):
            pkg = self._fresh_index(reread).find(package)
            if pkg is not None and pkg.share is not None:
                try:
                    return pkg.share.resolve(strict=True)
                except (OSError, RuntimeError):
                    return None
        return None

    def _all_shares(self) -> list[Path]:
        index = self._fresh_index(False)
        with self._lock:
            if self._roots is not None:
                return self._roots
        roots = []
        for pkg in index.packages().values():
            if pkg.share is not None:
                try:
                    roots.append(pkg.share.resolve(strict=True))
                except (OSError, RuntimeError):
                    continue
        with self._lock:
            self._roots = roots
        return roots


def _check_segments(path: str, uri: str) -> None:
    if '\x00' in path or '\\' in path or '..' in path.split('/'):
        raise AssetError(f'Refused path in {_shown(uri)}')


def _shown(uri: str) -> str:
    """A URI for a message: printable, bounded."""
    text = uri.encode('unicode_escape').decode('ascii')
    return text if len(text) <= 200 else text[:200] + '…'
