"""Publishers and listeners living in the test process, for exercising the topic verbs.

They run on threads of the test's own ros2lite context, so an in-process CLI call (the `run`
fixture) or a CLI subprocess can talk to them over the session router.
"""

from __future__ import annotations

import threading
import time
import uuid
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from ros2lite.node import Node
from tests.spinning import Listener


class Talker:
    """Publishes `make(i)` for i = 1, 2, … at a steady rate (absolute schedule, no drift)."""

    def __init__(
        self,
        ctx: Any,
        topic: str,
        type_name: str,
        make: Callable[[int], Any],
        rate: float,
        qos: Any,
        node_name: str,
        count: int | None,
    ) -> None:
        self.node = Node(node_name, context=ctx, enable_rosout=False)
        self.pub = self.node.create_publisher(type_name, topic, qos)
        self.make = make
        self.period = 1.0 / rate
        self.count = count
        self.sent = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._loop, daemon=True)
        self._thread.start()

    def _loop(self) -> None:
        start = time.monotonic()
        while not self._stop.is_set() and (self.count is None or self.sent < self.count):
            self.pub.publish(self.make(self.sent + 1))
            self.sent += 1
            self._stop.wait(max(0.0, start + self.sent * self.period - time.monotonic()))

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(5)
        self.node.destroy_node()


@pytest.fixture
def talker(ros_context: Any) -> Iterator[Callable[..., Talker]]:
    """Factory: talker(topic, type_name, make, rate=50, qos=10, node_name='talker')."""
    made: list[Talker] = []

    def start(
        topic: str,
        type_name: str,
        make: Callable[[int], Any],
        *,
        rate: float = 50.0,
        qos: Any = 10,
        node_name: str = 'talker',
        count: int | None = None,
    ) -> Talker:
        t = Talker(ros_context, topic, type_name, make, rate, qos, node_name, count)
        made.append(t)
        return t

    yield start
    for t in made:
        t.stop()


@pytest.fixture
def listener(ros_context: Any) -> Iterator[Callable[..., Listener]]:
    """Factory: listener(topic, type_name, qos=10)."""
    made: list[Listener] = []

    def start(topic: str, type_name: str, qos: Any = 10) -> Listener:
        lst = Listener(ros_context, topic, type_name, qos)
        made.append(lst)
        return lst

    yield start
    for lst in made:
        lst.stop()


@pytest.fixture
def topic() -> str:
    """A topic name no other test uses."""
    return f'/t_{uuid.uuid4().hex[:10]}'


def graph(ctx: Any) -> list[Any]:
    from ros2lite.graph import snapshot

    return snapshot(ctx.session, ctx.domain_id)


def has_endpoint(ctx: Any, topic: str, kind: str, node_name: str | None = None) -> bool:
    """True once the graph shows a publisher ('MP') / subscription ('MS') on the topic."""
    return any(
        e.kind.value == kind
        and e.topic_name == topic
        and (node_name is None or e.node_name == node_name)
        for e in graph(ctx)
    )


class Watch:
    """Reads a long-running CLI process's stdout line by line while the test goes on."""

    def __init__(self, proc: Any) -> None:
        self.proc = proc
        self.lines: list[str] = []
        self._thread = threading.Thread(target=self._read, daemon=True)
        self._thread.start()

    def _read(self) -> None:
        for line in self.proc.stdout:
            self.lines.append(line)

    @property
    def text(self) -> str:
        return ''.join(self.lines)

    def interrupt(self) -> tuple[int, str]:
        """Ctrl-C; returns (exit status, stderr)."""
        import signal

        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGINT)
        try:
            self.proc.wait(10)
        except Exception:
            self.proc.kill()
            self.proc.wait()
        self._thread.join(5)
        return self.proc.returncode, self.proc.stderr.read()
