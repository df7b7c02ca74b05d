"""When a node may start the daemon, and when the router is someone else's business."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from ros2lite import daemon
from ros2lite.daemon.connect import autostart_enabled, open_node_session

from .conftest import free_port


@pytest.mark.parametrize(
    "env, enabled",
    [
        ({}, True),
        ({"ROS2LITE_NO_DAEMON": "0"}, True),
        ({"ROS2LITE_NO_DAEMON": "1"}, False),
        ({"ROS2LITE_NO_DAEMON": "yes"}, False),
        ({"ZENOH_ROUTER_CHECK_ATTEMPTS": "0"}, False),  # the rmw_zenoh way: the user's router
        ({"ZENOH_ROUTER_CHECK_ATTEMPTS": ""}, True),
    ],
)
def test_autostart_enabled(env: dict[str, str], enabled: bool) -> None:
    assert autostart_enabled(env) is enabled


def test_node_starts_the_daemon_at_its_endpoint(
    endpoint: str, runtime: Path, monkeypatch: pytest.MonkeyPatch, capfd: Any
) -> None:
    monkeypatch.setenv("ROS2LITE_ROUTER", endpoint)
    session = open_node_session()
    try:
        assert session.info.routers_zid()
        st = daemon.status(endpoint)
        assert st.ours and st.info is not None
        assert [str(z) for z in session.info.routers_zid()] == [st.info.zid]
    finally:
        session.close()
    err = capfd.readouterr().err
    assert err.count("\n") == 1 and "started the ros2lite daemon" in err


def test_no_daemon_for_a_router_the_config_names(
    endpoint: str, runtime: Path, monkeypatch: pytest.MonkeyPatch, capfd: Any
) -> None:
    """An override or config file that names the router makes it the user's to run."""
    elsewhere = f"tcp/127.0.0.1:{free_port()}"
    monkeypatch.setenv("ROS2LITE_ROUTER", endpoint)
    monkeypatch.setenv("ZENOH_CONFIG_OVERRIDE", f'connect/endpoints=["{elsewhere}"]')
    session = open_node_session()
    session.close()
    assert not daemon.status(endpoint).running
    assert not daemon.status(elsewhere).running
    err = capfd.readouterr().err
    assert f"no Zenoh router answers at {elsewhere}: running without one" in err


def test_a_daemon_started_at_a_named_endpoint_is_said_with_the_likely_typo(
    endpoint: str, runtime: Path
) -> None:
    """At the default endpoint starting the daemon is silent (the quick start's promise);
    at another one it is said, and when a router answers at the default one, that the
    endpoint may be mistyped."""
    import zenoh

    from ros2lite.daemon.connect import started_elsewhere
    from ros2lite.transport.config import router_config

    assert started_elsewhere(endpoint, 42, default=endpoint) is None
    assert started_elsewhere("tcp/127.0.0.1:7447", 42) is None
    assert started_elsewhere("tls/127.0.0.1:7447", 42, secure=True) is None
    typo = f"tcp/127.0.0.1:{free_port()}"
    quiet = started_elsewhere(typo, 42, default=endpoint)  # nothing answers at `endpoint`
    assert quiet == (
        f"no Zenoh router answered at {typo}: started the ros2lite daemon there (pid 42), a "
        "graph of its own at the endpoint --router or ROS2LITE_ROUTER named ('ros2lite "
        f"--router {typo} daemon stop' ends it)"
    )
    router = zenoh.open(router_config(endpoint, env={}))
    try:
        said = started_elsewhere(typo, 42, default=endpoint)
    finally:
        router.close()
    assert said is not None
    assert (
        f"ROS2LITE_ROUTER named; a router answers at {endpoint}: is the endpoint mistyped?" in said
    )
