"""What the bridge's parts share, as public fields of one object: the node, the settings, the
SDK's context and server, the types found unknown, and the status line every part reports
through. Each part (channels, client publishing, services, parameters, assets) is an object
holding this state and owning the rest of what it needs, so no part reads another's
private attributes."""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import foxglove
from foxglove.websocket import StatusLevel, WebSocketServer

if TYPE_CHECKING:
    from ros2lite.node import Node

__all__ = ['BridgeState', 'Say', 'Settings', 'compile_patterns', 'matches']

Say = Callable[[str], object]

DEFAULT_CAPABILITIES = [
    'clientPublish',
    'parameters',
    'parametersSubscribe',
    'services',
    'connectionGraph',
    'assets',
]
# what the C++ bridge's `asset_uri_allowlist` admits by default (mesh, texture and robot
# description files), for package:// and, here, file:// URIs too
DEFAULT_ASSET_ALLOWLIST = [
    r'^(?:package://(?:[-\w%]+/)*|file:///(?:[-\w%.]+/)*)'
    r'[-\w%.]+\.(?:dae|fbx|glb|gltf|jpeg|jpg|mtl|obj|png|stl|tif|tiff|urdf|webp|xacro)$'
]


@dataclass
class Settings:
    """The bridge's parameters, as the C++ bridge names them."""

    port: int = 8765
    address: str = '127.0.0.1'
    topic_whitelist: list[str] = field(default_factory=lambda: ['.*'])
    service_whitelist: list[str] = field(default_factory=lambda: ['.*'])
    param_whitelist: list[str] = field(default_factory=lambda: ['.*'])
    client_topic_whitelist: list[str] = field(default_factory=lambda: ['.*'])
    asset_uri_allowlist: list[str] = field(default_factory=lambda: list(DEFAULT_ASSET_ALLOWLIST))
    capabilities: list[str] = field(default_factory=lambda: list(DEFAULT_CAPABILITIES))
    message_backlog_size: int = 1024
    send_buffer_limit: int = 10_000_000
    min_qos_depth: int = 1
    max_qos_depth: int = 25
    include_hidden: bool = False
    ignore_unresponsive_param_nodes: bool = True
    service_timeout: float = 5.0
    use_sim_time: bool = False
    tls: bool = False
    certfile: str = ''
    keyfile: str = ''


def compile_patterns(patterns: list[str], what: str) -> list[re.Pattern[str]]:
    """The regexes of a whitelist; a bad one is the user's error, named."""
    out = []
    for p in patterns:
        try:
            out.append(re.compile(p))
        except re.error as e:
            raise ValueError(f"invalid regular expression '{p}' in {what}: {e}") from None
    return out


def matches(patterns: list[re.Pattern[str]], name: str) -> bool:
    """Whether a whitelist admits `name` (a whole match of one of its patterns)."""
    return any(p.fullmatch(name) for p in patterns)


@dataclass
class BridgeState:
    """Set up once by `Bridge`; `server` is filled in when the server has started."""

    node: Node
    settings: Settings
    context: foxglove.Context
    own: str  # the bridge node's fully qualified name (its own entities are not shown)
    capabilities: set[str]
    warn: Say
    log: Say
    server: WebSocketServer | None = None
    unknown_types: set[str] = field(default_factory=set)  # types with no definition here

    def status(self, message: str, level: StatusLevel = StatusLevel.Warning) -> None:
        """Tell the log and every client (a status message)."""
        self.warn(message)
        if self.server is not None:
            self.server.publish_status(message, level)
