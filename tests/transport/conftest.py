"""Fixtures for transport tests: free loopback ports and an in-process Zenoh router."""

from __future__ import annotations

import random
from collections.abc import Iterator

import pytest

from tests.spinning import free_port


@pytest.fixture
def dead_endpoint() -> str:
    return f"tcp/127.0.0.1:{free_port()}"


@pytest.fixture
def private_domain(monkeypatch: pytest.MonkeyPatch) -> int:
    """A ROS_DOMAIN_ID no other test run is likely to use, and a clean Zenoh environment."""
    domain = random.randint(100, 232)
    monkeypatch.setenv("ROS_DOMAIN_ID", str(domain))
    for var in (
        "ZENOH_CONFIG_OVERRIDE",
        "ZENOH_SESSION_CONFIG_URI",
        "ZENOH_ROUTER_CONFIG_URI",
        "ROS2LITE_ROUTER",
    ):
        monkeypatch.delenv(var, raising=False)
    return domain


@pytest.fixture(scope="module")
def live_router() -> Iterator[str]:
    """A real Zenoh router, in this process, on a free loopback port; yields its endpoint."""
    import zenoh

    from ros2lite.transport.config import router_config

    endpoint = f"tcp/127.0.0.1:{free_port()}"
    session = zenoh.open(router_config(endpoint, env={}))
    try:
        yield endpoint
    finally:
        session.close()
