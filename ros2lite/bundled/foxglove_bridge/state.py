"""What the bridge's parts share: the node, the settings, the server, the types found
unknown, and the warning status line every part reports through."""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import TYPE_CHECKING

import foxglove
from foxglove.websocket import StatusLevel, WebSocketServer

if TYPE_CHECKING:
    from ros2lite.bundled.foxglove_bridge.bridge import Settings
    from ros2lite.node import Node


def _matches(patterns: list[re.Pattern[str]], name: str) -> bool:
    return any(p.fullmatch(name) for p in patterns)


class BridgeState:
    """The state `Bridge.__init__` sets up and its parts (channels, client publishing,
    services) read; each part declares what else it owns."""

    node: Node
    settings: Settings
    server: WebSocketServer | None
    _warn: Callable[[str], object]
    _own: str
    _context: foxglove.Context
    _caps: set[str]
    _unknown_types: set[str]

    if TYPE_CHECKING:  # the services part's, called when the graph changes

        def _refresh_services(self, services: dict[str, str]) -> None: ...

    def _status(self, message: str, level: StatusLevel = StatusLevel.Warning) -> None:
        self._warn(message)
        if self.server is not None:
            self.server.publish_status(message, level)
