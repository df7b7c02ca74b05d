"""One UDP multicast datagram out or in: does this network pass multicast?

ros2cli's check (group 225.0.0.1, port 49150, `Hello World!`), plus a choice of interface.
What the answer means here: ros2lite, like rmw_zenoh, does not need multicast — nodes find
each other through the Zenoh router over TCP — so multicast matters only when Zenoh's
multicast scouting is turned on (group :data:`ZENOH_SCOUTING`).
"""

from __future__ import annotations

import ipaddress
import socket
import struct

from ros2lite.exceptions import Ros2liteError

__all__ = [
    'DEFAULT_GROUP',
    'DEFAULT_PORT',
    'HELLO',
    'ZENOH_SCOUTING',
    'MulticastError',
    'MulticastReceiver',
    'MulticastSender',
    'check_settings',
    'receive',
    'send',
]

DEFAULT_GROUP = '225.0.0.1'
DEFAULT_PORT = 49150
HELLO = b'Hello World!'
ZENOH_SCOUTING = '224.0.0.224:7446'  # zenoh's default scouting/multicast/address


class MulticastError(Ros2liteError, OSError):
    """Bad multicast settings, or the system refused the socket operation."""


def check_settings(
    group: str, port: int, interface: str | None = None, ttl: int | None = None
) -> None:
    """MulticastError unless `group` is an IPv4 multicast address, `port` and `ttl` in
    range and `interface` an IPv4 address."""
    try:
        address = ipaddress.IPv4Address(group)
    except ValueError:
        raise MulticastError(f"'{group}' is not an IPv4 address") from None
    if not address.is_multicast:
        raise MulticastError(f"'{group}' is not a multicast address (224.0.0.0/4)")
    if not 0 < port < 65536:
        raise MulticastError(f'port {port} is out of range (1-65535)')
    if ttl is not None and not 0 <= ttl <= 255:
        raise MulticastError(f'TTL {ttl} is out of range (0-255)')
    if interface is not None:
        try:
            ipaddress.IPv4Address(interface)
        except ValueError:
            raise MulticastError(f"'{interface}' is not the IPv4 address of an interface") from None


def _default_interface(group: str) -> str:
    """The local address the routing table would send `group` from (no packet is sent)."""
    probe = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    try:
        probe.connect((group, 1))
        return str(probe.getsockname()[0])
    except OSError:
        return '0.0.0.0'
    finally:
        probe.close()


class MulticastSender:
    """A socket that sends datagrams to `group`:`port` from `interface` (default: the routed
    one). TTL 0 keeps them on this host; None leaves the system default (1: this subnet)."""

    def __init__(
        self,
        *,
        group: str = DEFAULT_GROUP,
        port: int = DEFAULT_PORT,
        ttl: int | None = None,
        interface: str | None = None,
    ) -> None:
        check_settings(group, port, interface, ttl)
        self.group, self.port = group, port
        self._sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
        try:
            if ttl is not None:
                ttl_bytes = struct.pack('B', ttl)
                self._sock.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, ttl_bytes)
            iface = interface or _default_interface(group)
            self._sock.setsockopt(
                socket.IPPROTO_IP, socket.IP_MULTICAST_IF, socket.inet_aton(iface)
            )
        except OSError as e:
            self._sock.close()
            raise MulticastError(f'cannot send to {group}:{port}: {e.strerror or e}') from None

    def send(self, data: bytes = HELLO) -> None:
        """One datagram out; MulticastError when the system refuses it."""
        try:
            self._sock.sendto(data, (self.group, self.port))
        except OSError as e:
            raise MulticastError(
                f'cannot send to {self.group}:{self.port}: {e.strerror or e}'
            ) from None

    def close(self) -> None:
        """Let the socket go."""
        self._sock.close()


class MulticastReceiver:
    """A socket that has joined `group`:`port` on `interface` (default: any) and takes what
    arrives, one datagram at a time, until closed."""

    def __init__(
        self, *, group: str = DEFAULT_GROUP, port: int = DEFAULT_PORT, interface: str | None = None
    ) -> None:
        check_settings(group, port, interface)
        self.group, self.port = group, port
        self._sock = socket.socket(socket.AF_INET, socket.SOCK_DGRAM, socket.IPPROTO_UDP)
        local = socket.inet_aton(interface) if interface else struct.pack('!I', socket.INADDR_ANY)
        self._membership = socket.inet_aton(group) + local
        try:
            self._sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            if hasattr(socket, 'SO_REUSEPORT'):
                self._sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEPORT, 1)
            self._sock.bind(('', port))
            self._sock.setsockopt(socket.IPPROTO_IP, socket.IP_ADD_MEMBERSHIP, self._membership)
        except OSError as e:
            self._sock.close()
            raise MulticastError(
                f'cannot join {group}:{port}'
                + (f' on {interface}' if interface else '')
                + f': {e.strerror or e}'
            ) from None

    def receive(self, timeout: float | None = None) -> tuple[bytes, tuple[str, int]]:
        """The next datagram and its sender's (host, port); TimeoutError after `timeout` s."""
        self._sock.settimeout(timeout)
        try:
            data, sender = self._sock.recvfrom(4096)
        except TimeoutError:
            raise TimeoutError(
                f'no datagram to {self.group}:{self.port} within {timeout:g} s'
            ) from None
        return data, (str(sender[0]), int(sender[1]))

    def close(self) -> None:
        """Leave the group and let the socket go."""
        try:
            self._sock.setsockopt(socket.IPPROTO_IP, socket.IP_DROP_MEMBERSHIP, self._membership)
        except OSError:
            pass  # already gone with the interface: nothing left to leave
        finally:
            self._sock.close()


def send(
    data: bytes = HELLO,
    *,
    group: str = DEFAULT_GROUP,
    port: int = DEFAULT_PORT,
    ttl: int | None = None,
    interface: str | None = None,
) -> None:
    """Send one datagram to `group`:`port` (see :class:`MulticastSender`)."""
    sender = MulticastSender(group=group, port=port, ttl=ttl, interface=interface)
    try:
        sender.send(data)
    finally:
        sender.close()


def receive(
    *,
    group: str = DEFAULT_GROUP,
    port: int = DEFAULT_PORT,
    timeout: float | None = None,
    interface: str | None = None,
) -> tuple[bytes, tuple[str, int]]:
    """Wait for one datagram to `group`:`port` (joined on `interface`, default: any) and
    return it with the sender's (host, port); TimeoutError after `timeout` s."""
    receiver = MulticastReceiver(group=group, port=port, interface=interface)
    try:
        return receiver.receive(timeout)
    finally:
        receiver.close()
