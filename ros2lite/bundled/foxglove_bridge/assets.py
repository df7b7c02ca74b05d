"""Assets (the protocol's `fetchAsset`): a robot's meshes and textures by `package://` or
`file://` URI, so a URDF robot shows in Foxglove and Lichtblick.

Only files inside the share folder of a package the package index knows are served, as
`ros2lite.urdf.resources` resolves them (the one place of that rule), and of those only a
regular file on the URI allowlist, at most `MAX_ASSET_BYTES`. Anything else of the filesystem
is refused with one line, the protocol's error status.
"""

from __future__ import annotations

import os
import re
import stat
from pathlib import Path

from ros2lite.bundled.foxglove_bridge.state import matches
from ros2lite.exceptions import Ros2liteError
from ros2lite.urdf import ResourceNotFoundError, UrdfError
from ros2lite.urdf.resources import ResourceResolver, shown

__all__ = ['MAX_ASSET_BYTES', 'AssetError', 'PackageAssets']

# a mesh larger than this is refused (the client's WebSocket buffers the whole reply)
MAX_ASSET_BYTES = 64 * 1024 * 1024


class AssetError(Ros2liteError, ValueError):
    """A URI the bridge will not serve; the message goes to the client as is."""


class PackageAssets:
    """Serves files of package share folders by URI (`fetch`, the SDK's asset handler)."""

    def __init__(self, allowlist: list[re.Pattern[str]], *, limit: int = MAX_ASSET_BYTES) -> None:
        self._allowlist = allowlist
        self._limit = limit
        self._resolver = ResourceResolver()

    def fetch(self, uri: str) -> bytes:
        """The bytes of the file `uri` names; AssetError (one line) when it is not served."""
        if len(uri) > 4096 or not matches(self._allowlist, uri):
            raise AssetError(f'Asset URI not allowed: {shown(uri)}')
        path = self.resolve(uri)
        return self._read(path, uri)

    def resolve(self, uri: str) -> Path:
        """The file inside a package share folder that `uri` names (resolved)."""
        try:
            return self._resolver.resolve(uri)
        except ResourceNotFoundError:
            raise AssetError(f'Asset not found: {shown(uri)}') from None
        except UrdfError as e:
            raise AssetError(str(e)) from None

    def _read(self, path: Path, uri: str) -> bytes:
        try:
            # no FIFO or device blocks us; the last component is not swapped for a link
            fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOFOLLOW | os.O_CLOEXEC)
        except OSError as e:
            raise AssetError(f'Cannot read {shown(uri)}: {e.strerror}') from None
        with os.fdopen(fd, 'rb') as f:
            info = os.fstat(f.fileno())
            if not stat.S_ISREG(info.st_mode):
                raise AssetError(f'Not a regular file: {shown(uri)}')
            if info.st_size > self._limit:
                raise AssetError(
                    f'Asset too large ({info.st_size} bytes, at most {self._limit}): {shown(uri)}'
                )
            data = f.read(self._limit + 1)
        if len(data) > self._limit:
            raise AssetError(f'Asset too large (at most {self._limit} bytes): {shown(uri)}')
        return data
