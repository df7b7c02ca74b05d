"""An alien (bare zenoh) Fibonacci action server for the action verbs to talk to."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import pytest

from tests.action.alien import AlienFibonacciServer


@pytest.fixture
def alien_session(ros_router: str) -> Iterator[Any]:
    import zenoh
    conf = zenoh.Config()
    conf.insert_json5('mode', '"client"')
    conf.insert_json5('connect/endpoints', f'["{ros_router}"]')
    conf.insert_json5('scouting/multicast/enabled', 'false')
    conf.insert_json5('timestamping/enabled', 'true')   # advanced publishers need it
    session = zenoh.open(conf)
    try:
        yield session
    finally:
        session.close()


@pytest.fixture
def alien_server(alien_session: Any) -> Iterator[AlienFibonacciServer]:
    import os
    server = AlienFibonacciServer(alien_session, int(os.environ['ROS_DOMAIN_ID']))
    try:
        yield server
    finally:
        server.close()
