"""`foxglove_bridge`: the live graph for Foxglove (and Lichtblick) on a WebSocket port.

`ros2lite run foxglove_bridge foxglove_bridge --ros-args -p port:=8765` as with the C++
package; parameters are read once at start, as there. It listens on loopback unless
`address` says otherwise: the bridge lets a client publish, call services and set parameters.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any

from ros2lite.bundled.runner import run_main

if TYPE_CHECKING:
    from ros2lite.bundled.foxglove_bridge.bridge import Settings
    from ros2lite.node import Node


def read_settings(node: Node) -> Settings:
    """The bridge's parameters, declared on `node` with the C++ bridge's names and defaults
    (save `address`: loopback here)."""
    from ros2lite.bundled.foxglove_bridge.bridge import Settings

    values: dict[str, Any] = {}
    for f in dataclasses.fields(Settings):
        if f.name == 'use_sim_time':
            continue  # every node declares it
        default = Settings().__getattribute__(f.name)
        values[f.name] = node.declare_parameter(f.name, default).value
    values['use_sim_time'] = bool(node.get_parameter('use_sim_time').value)
    settings = Settings(**values)
    if not 0 <= settings.port <= 65535:
        raise ValueError(f'port must be 0..65535, not {settings.port}')
    return settings


def _serve() -> None:
    import ros2lite
    from ros2lite.bundled.foxglove_bridge.bridge import Bridge
    from ros2lite.node import Node

    node = Node('foxglove_bridge')
    try:
        bridge = Bridge(node, read_settings(node))
        try:
            bridge.start()
        except RuntimeError as e:  # the SDK's: the port is taken, a certificate is bad
            raise ValueError(f'foxglove_bridge: cannot start the server: {e}') from None
        _warn_if_secured(node, bridge.port)
        try:
            ros2lite.spin(node)
        finally:
            bridge.close()
    finally:
        node.destroy_node()


def _warn_if_secured(node: Node, port: int) -> None:
    """A bridge under an enclave lends that enclave to whoever reaches its port, since
    WebSocket clients show no certificate: say so, once, and how to close the door."""
    from ros2lite.security.environment import resolve, security_enabled

    if not security_enabled() or resolve() is None:
        return
    address = node.get_parameter('address').value
    scheme = 'wss' if node.get_parameter('tls').value else 'ws'
    node.get_logger().warning(
        f'security is on: any local user who reaches {scheme}://{address}:{port} publishes, calls '
        f'services and sets parameters as enclave {node.context.enclave}; bind `address` '
        'where only trusted users reach it and firewall the port, or run no bridge under an '
        'enclave'
    )


def main(args: list[str] | None = None) -> int:
    """`foxglove_bridge`'s entry point."""
    return run_main(_serve, args)


if __name__ == '__main__':
    raise SystemExit(main())
