"""Shared test helpers: poll or spin until something happened, and free loopback ports."""

from __future__ import annotations

import socket
import time
from collections.abc import Callable
from typing import Any

import pytest


def free_port() -> int:
    """A loopback TCP port nobody listens on right now (never rmw_zenohd's 7447)."""
    while True:
        with socket.socket() as sock:
            sock.bind(('127.0.0.1', 0))
            port = int(sock.getsockname()[1])
        if port != 7447:
            return port


def wait_until(
    predicate: Callable[[], Any],
    timeout: float = 10.0,
    interval: float = 0.05,
    step: Callable[[], Any] | None = None,
) -> Any:
    """Until predicate() is truthy, sleep `interval` (or run `step`); returns its value or
    fails the test on timeout."""
    deadline = time.monotonic() + timeout
    while True:
        value = predicate()
        if value:
            return value
        if time.monotonic() > deadline:
            pytest.fail(f'condition not met within {timeout} s')
        if step is None:
            time.sleep(interval)
        else:
            step()


def spin_until(executor: Any, predicate: Callable[[], Any], timeout: float = 5.0) -> Any:
    """Run `executor.spin_once` until predicate() is truthy; fail the test on timeout."""
    return wait_until(predicate, timeout, step=lambda: executor.spin_once(timeout_sec=0.05))


def spin_for(executor: Any, seconds: float) -> None:
    """Run callbacks for a fixed time (to show that something does *not* arrive)."""
    deadline = time.monotonic() + seconds
    while (left := deadline - time.monotonic()) > 0:
        executor.spin_once(timeout_sec=min(left, 0.05))


def queued(sub: Any) -> list[bytes]:
    """(white box) The payloads a typed subscription has received and not yet delivered,
    moving what waits in Zenoh's channel into its queue first (as the executor would, before
    delivering). Call it only while no executor spins the subscription."""
    source = sub._source
    if source.kept:  # the channel waits for the executor to park in it: look, as it would
        source.poll()
    if not source._armed:
        source._pull(1 << 20)
    return [sample.payload.to_bytes() for sample in source._pending]


def wait_matched(pub: Any, sub_count: int = 1, timeout: float = 5.0) -> None:
    """Wait until the graph shows the publisher's subscriptions (so no early sample is lost)."""
    deadline = time.monotonic() + timeout
    while pub.get_subscription_count() < sub_count:
        if time.monotonic() > deadline:
            pytest.fail('subscription never appeared in the graph')
        time.sleep(0.02)


class Listener:
    """Collects a topic's messages (or, raw, its CDR bytes and arrival times) on an
    executor thread of the test's context."""

    def __init__(self, ctx: Any, topic: str, type_name: Any, qos: Any, raw: bool = False) -> None:
        import threading
        import uuid

        from ros2lite.executors import SingleThreadedExecutor
        from ros2lite.node import Node

        self.node = Node(f'listener_{uuid.uuid4().hex[:6]}', context=ctx, enable_rosout=False)
        self.messages: list[Any] = []
        self.arrivals: list[int] = []  # raw only: when each sample arrived (ns, wall clock)

        def keep(data: bytes, info: Any) -> None:
            self.arrivals.append(info.received_timestamp)
            self.messages.append(data)

        if raw:
            self.node.create_subscription(type_name, topic, keep, qos, raw=True)
        else:
            self.node.create_subscription(type_name, topic, self.messages.append, qos)
        self._executor = SingleThreadedExecutor(context=ctx)
        self._executor.add_node(self.node)
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._spin, daemon=True)
        self._thread.start()

    def _spin(self) -> None:
        while not self._stop.is_set():
            self._executor.spin_once(0.05)

    def stop(self) -> None:
        self._stop.set()
        self._thread.join(5)
        self.node.destroy_node()


def wait_for_route(alien: Any, node: Any, topic: str) -> None:
    """Until samples `alien` (a session of its own, through the router) puts on `topic` reach
    `node`'s subscription: its token, declared after its subscriber on the same link, has
    reached the router (the node's own graph lists its entities at once, which says nothing
    about that router)."""
    from ros2lite.transport.session import liveliness_keys

    tokens = [s._ep.token_key for s in node.subscriptions if s.topic_name == topic]
    assert tokens, f'{node.get_name()} has no subscription on {topic}'
    wait_until(lambda: tokens[0] in liveliness_keys(alien, node.context.domain_id, 1.0))
