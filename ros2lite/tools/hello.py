"""`doctor hello` (and `wtf hello`): a String on a topic and a datagram to the multicast
group every period, and a count of what this host heard from every other, as ros2doctor's
`hello` does; kept apart from the checks, which it shares nothing with.
"""

from __future__ import annotations

import os
import re
import socket
import threading
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ros2lite.msgs.std_msgs.msg import String
    from ros2lite.node import Node

__all__ = ['HELLO_TOPIC', 'Hello', 'HelloCounts', 'hello_node_name']

HELLO_TOPIC = '/canyouhearme'
_RECEIVE_POLL = 0.2  # how often the multicast thread looks whether it should stop


def hello_node_name() -> str:
    """ros2doctor's node name for `hello`: the host name (made a valid name) and the pid."""
    host = re.sub(r'[^0-9a-zA-Z_]', '_', socket.gethostname())
    return f'ros2doctor_{host}_{os.getpid()}_node'


@dataclass
class HelloCounts:
    """What went out, and what came in from each other host, since the last reset."""

    published: int = 0
    sent: int = 0
    subscribed: dict[str, int] = field(default_factory=dict)
    received: dict[str, int] = field(default_factory=dict)


class Hello:
    """Every :meth:`emit` publishes `hello, it's me <host>` on `topic` and sends it to the
    multicast group; hellos of other hosts are counted per host, by topic (on the node's
    executor) and by multicast (on a thread of its own). Own hellos are not counted: one
    host alone sees only what it sent."""

    def __init__(
        self,
        node: Node,
        topic: str = HELLO_TOPIC,
        *,
        group: str | None = None,
        port: int | None = None,
        ttl: int | None = None,
        interface: str | None = None,
    ) -> None:
        from ros2lite.msgs.std_msgs.msg import String
        from ros2lite.qos import qos_profile_system_default
        from ros2lite.tools.multicast import (
            DEFAULT_GROUP,
            DEFAULT_PORT,
            MulticastReceiver,
            MulticastSender,
        )

        self.host = socket.gethostname()
        self.message = String(data=f"hello, it's me {self.host}")
        self._lock = threading.Lock()
        self._counts = HelloCounts()
        group, port = group or DEFAULT_GROUP, port or DEFAULT_PORT
        self._receiver = MulticastReceiver(group=group, port=port, interface=interface)
        try:
            self._sender = MulticastSender(group=group, port=port, ttl=ttl, interface=interface)
        except BaseException:
            self._receiver.close()
            raise
        self._pub = node.create_publisher(String, topic, qos_profile_system_default)
        self._sub = node.create_subscription(String, topic, self._heard, qos_profile_system_default)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._receive, name='hello-multicast', daemon=True)
        self._thread.start()

    def emit(self) -> None:
        """One hello out, on the topic and to the multicast group."""
        with self._lock:
            self._counts.published += 1
        self._pub.publish(self.message)
        with self._lock:
            self._counts.sent += 1
        self._sender.send(self.message.data.encode())

    def take_counts(self) -> HelloCounts:
        """The counts so far; counting starts again from zero."""
        with self._lock:
            counts, self._counts = self._counts, HelloCounts()
        return counts

    def close(self) -> None:
        """Stop receiving and let the sockets go (the node's endpoints go with the node)."""
        self._stop.set()
        self._thread.join()
        self._receiver.close()
        self._sender.close()

    def _count(self, table: str, text: str) -> None:
        host = text.split()[-1] if text.split() else ''
        if host != self.host:
            with self._lock:
                counts: dict[str, int] = getattr(self._counts, table)
                counts[host] = counts.get(host, 0) + 1

    def _heard(self, msg: String) -> None:
        self._count('subscribed', msg.data)

    def _receive(self) -> None:
        while not self._stop.is_set():
            try:
                data, _sender = self._receiver.receive(_RECEIVE_POLL)
            except TimeoutError:
                continue
            except OSError:
                return  # the socket went away under us: nothing more will arrive
            self._count('received', data.decode('utf-8', errors='replace'))
