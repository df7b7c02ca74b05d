"""Which router and domain a process talks to, from the environment (no zenoh needed)."""

from __future__ import annotations

import sys

import pytest

from ros2lite.transport import endpoints as ep
from ros2lite.transport.errors import ConfigError


def test_reading_them_loads_no_zenoh() -> None:
    import subprocess

    code = (
        'import sys, ros2lite.transport.endpoints as e; '
        'e.router_endpoint(); e.domain_id(); print("zenoh" in sys.modules)'
    )
    out = subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == 'False'


def test_domain_id() -> None:
    assert ep.domain_id({}) == 0
    assert ep.domain_id({"ROS_DOMAIN_ID": " 7 "}) == 7
    assert ep.domain_id({"ROS_DOMAIN_ID": "232"}) == 232
    with pytest.raises(ConfigError, match=r"0\.\.232, got 233"):
        ep.domain_id({"ROS_DOMAIN_ID": "233"})
    with pytest.raises(ConfigError, match="integer"):
        ep.domain_id({"ROS_DOMAIN_ID": "abc"})
    with pytest.raises(ConfigError):
        ep.domain_id({"ROS_DOMAIN_ID": "-1"})


def test_router_endpoint() -> None:
    assert ep.router_endpoint(env={}) == "tcp/127.0.0.1:7447"
    assert ep.router_endpoint(env={"ROS2LITE_ROUTER": "tcp/127.0.0.1:9"}) == "tcp/127.0.0.1:9"
    assert ep.router_endpoint("tcp/[::1]:5", env={"ROS2LITE_ROUTER": "x/y"}) == "tcp/[::1]:5"
    with pytest.raises(ConfigError, match="protocol"):
        ep.router_endpoint("localhost:7447", env={})


def test_endpoint_host_port() -> None:
    assert ep.endpoint_host_port("tcp/127.0.0.1:7447") == ("tcp", "127.0.0.1", 7447)
    assert ep.endpoint_host_port("tcp/[::1]:7447#iface=lo") == ("tcp", "::1", 7447)
    assert ep.endpoint_host_port("tls/localhost:1?x=y") == ("tls", "localhost", 1)
    assert ep.endpoint_host_port("unixsock-stream//tmp/sock") is None
    assert ep.endpoint_host_port("nonsense") is None


def test_router_check_attempts() -> None:
    assert ep.router_check_attempts({}) == 1
    assert ep.router_check_attempts({"ZENOH_ROUTER_CHECK_ATTEMPTS": " 3 "}) == 3
    assert ep.router_check_attempts({"ZENOH_ROUTER_CHECK_ATTEMPTS": "0"}) == 0
    assert ep.router_check_attempts({"ZENOH_ROUTER_CHECK_ATTEMPTS": "-1"}) == -1
    with pytest.raises(ConfigError, match="ZENOH_ROUTER_CHECK_ATTEMPTS must be an integer"):
        ep.router_check_attempts({"ZENOH_ROUTER_CHECK_ATTEMPTS": "many"})


def test_secure_default_is_handed_down() -> None:
    """transport knows nothing of security: whether the default router is the TLS one is
    the caller's value (ros2lite.daemon.connect decides it from ros2lite.security)."""
    assert ep.router_endpoint(env={}, secure=True) == "tls/127.0.0.1:7447"
    assert ep.router_endpoint(env={"ROS_SECURITY_ENABLE": "true"}) == "tcp/127.0.0.1:7447"
    assert ep.router_endpoint("tcp/127.0.0.1:9", env={}, secure=True) == "tcp/127.0.0.1:9"
