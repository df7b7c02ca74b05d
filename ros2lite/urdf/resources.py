"""Resource URIs of robot descriptions (`package://pkg/path`, `file:///abs/path`) to files,
confined to the share folders of packages ros2lite's package index knows: the one place this
resolution lives (the viewer's meshes and the Foxglove bridge's `fetchAsset` both call it).

The URI is percent-decoded, a `..` segment, a NUL or a backslash refused, the path resolved
(symlinks followed) and checked again against the share folders, so neither a crafted URI nor
a link inside a package leads anywhere else of the filesystem.
"""

from __future__ import annotations

import threading
import time
from pathlib import Path
from urllib.parse import unquote

from ros2lite.pkg.index import PackageIndex
from ros2lite.pkg.manifest import is_valid_package_name
from ros2lite.urdf.errors import ResourceNotFoundError, UrdfError

__all__ = ['ResourceResolver', 'resolve_resource']

# the package index is read again at most this often (seconds), when a lookup misses
REREAD_PERIOD = 5.0
MAX_URI_CHARS = 4096


class ResourceResolver:
    """Resolves resource URIs through one package index, read again (at most every few
    seconds) when a package is missing, so a workspace built meanwhile is found."""

    def __init__(self, index: PackageIndex | None = None) -> None:
        self._lock = threading.Lock()
        self._fixed = index is not None
        self._index = index
        self._read_at = time.monotonic()
        self._roots: list[Path] | None = None

    def resolve(self, uri: str) -> Path:
        """The existing file inside a package share folder that `uri` names (resolved)."""
        if len(uri) > MAX_URI_CHARS:
            raise UrdfError(f'Resource URI too long ({len(uri)} characters)')
        if uri.startswith('package://'):
            package, _, rest = unquote(uri[len('package://') :]).partition('/')
            if not is_valid_package_name(package):
                raise UrdfError(f'Not a package name in {shown(uri)}')
            share = self._share(package)
            if share is None:
                raise UrdfError(f"Package '{package}' not found (resource {shown(uri)})")
            _check_segments(rest, uri)
            roots = [share]
            target = share / rest
        elif uri.startswith('file://'):
            path = unquote(uri[len('file://') :])
            if not path.startswith('/'):
                raise UrdfError(f'Only absolute file:// URIs are resolved: {shown(uri)}')
            _check_segments(path, uri)
            roots = self._all_shares()
            target = Path(path)
        else:
            raise UrdfError(f'Unsupported resource URI scheme (package://, file://): {shown(uri)}')
        try:
            found = target.resolve(strict=True)
        except (OSError, RuntimeError):
            raise ResourceNotFoundError(f'Resource not found: {shown(uri)}') from None
        if not any(found.is_relative_to(root) for root in roots):
            # a symlink (or a file:// path) leading out of every package's share folder
            raise UrdfError(f'Resource outside the package share folders: {shown(uri)}')
        return found

    def _fresh_index(self, reread: bool) -> PackageIndex:
        with self._lock:
            now = time.monotonic()
            stale = reread and not self._fixed and now - self._read_at >= REREAD_PERIOD
            if self._index is None or stale:
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


_DEFAULT: list[ResourceResolver] = []
_DEFAULT_LOCK = threading.Lock()


def resolve_resource(uri: str) -> Path:
    """The file `uri` (`package://` or `file://`) names inside a package share folder;
    UrdfError, or its ResourceNotFoundError (also a FileNotFoundError), in one line otherwise."""
    with _DEFAULT_LOCK:
        if not _DEFAULT:
            _DEFAULT.append(ResourceResolver())
        resolver = _DEFAULT[0]
    return resolver.resolve(uri)


def _check_segments(path: str, uri: str) -> None:
    if '\x00' in path or '\\' in path or '..' in path.split('/'):
        raise UrdfError(f'Refused path in {shown(uri)}')


def shown(uri: str) -> str:
    """A URI for a message: printable, bounded."""
    text = uri.encode('unicode_escape').decode('ascii')
    return text if len(text) <= 200 else text[:200] + '…'
