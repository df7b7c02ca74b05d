from __future__ import annotations

import json
import threading
import time
from pathlib import Path

import pytest
import zenoh

from ros2lite.transport import config as cfg
from ros2lite.transport.errors import ConfigError, RouterUnavailableError
from ros2lite.transport.keys import liveliness_subscription_key, node_token, topic_key
from ros2lite.transport.open import open_session
from tests.spinning import wait_until


def get(config: zenoh.Config, key: str) -> object:
    return json.loads(config.get_json(key))


def test_parse_config_override() -> None:
    text = 'mode="peer"; connect/endpoints=["tcp/a:1","tcp/b;c:2"];;x={a:"b;c"}; '
    assert cfg.parse_config_override(text) == [
        ("mode", '"peer"'),
        ("connect/endpoints", '["tcp/a:1","tcp/b;c:2"]'),
        ("x", '{a:"b;c"}'),
    ]
    assert cfg.parse_config_override("") == []
    with pytest.raises(ConfigError, match="key=json5"):
        cfg.parse_config_override("mode")


def test_session_defaults() -> None:
    config = cfg.session_config("tcp/127.0.0.1:1234", env={})
    assert get(config, "mode") == "client"
    assert get(config, "connect/endpoints") == ["tcp/127.0.0.1:1234"]
    assert get(config, "scouting/multicast/enabled") is False
    assert get(config, "timestamping/enabled") is True
    assert get(config, "transport/shared_memory/enabled") is False
    assert get(config, "listen/endpoints") == {"peer": ["tcp/127.0.0.1:0"]}
    env_config = cfg.session_config(env={"ROS2LITE_ROUTER": "tcp/127.0.0.1:99"})
    assert get(env_config, "connect/endpoints") == ["tcp/127.0.0.1:99"]


def test_node_sessions_are_peers_that_retry_the_router_often() -> None:
    config = cfg.session_config("tcp/127.0.0.1:1234", env={}, mode="peer")
    assert get(config, "mode") == "peer"
    # a peer opens without a router and keeps retrying it; a client gives up at once
    assert get(config, "connect/exit_on_failure") == {
        "router": False,
        "peer": False,
        "client": True,
    }
    assert get(config, "connect/timeout_ms") == {"router": -1, "peer": -1, "client": 1000}
    retry = get(config, "connect/retry")
    assert isinstance(retry, dict) and retry["period_max_ms"] <= 500
    assert get(config, "scouting/gossip/autoconnect") == {"router": [], "peer": ["router", "peer"]}


@pytest.mark.parametrize(
    "endpoint, mode",
    [
        ("tcp/127.0.0.1:7447", "peer"),
        ("tcp/localhost:7447", "peer"),
        ("tcp/[::1]:7447", "peer"),
        ("tcp/0.0.0.0:7447", "peer"),
        ("unixsock-stream//tmp/router.sock", "peer"),
        ("tcp/10.0.0.1:7447", "client"),
        ("tcp/robot.local:7447", "client"),
        ("udp/127.0.0.1:7447", "peer"),
    ],
)
def test_node_mode_is_peer_only_with_a_router_on_this_host(endpoint: str, mode: str) -> None:
    # our peers listen on loopback only, so a remote router could not introduce them
    assert cfg.node_session_mode(endpoint, env={}) == mode
    # the router the session really connects to decides
    override = {
        "ZENOH_CONFIG_OVERRIDE": f'connect/endpoints=["{endpoint}"]',
        "ROS2LITE_ROUTER": "tcp/127.0.0.1:7447",
    }
    assert cfg.node_session_mode(env=override) == mode


def test_router_admin_space_is_read_only() -> None:
    config = cfg.router_config("tcp/127.0.0.1:5", env={})
    assert get(config, "adminspace/enabled") is True
    assert get(config, "adminspace/permissions") == {"read": True, "write": False}


def test_config_override_is_applied() -> None:
    env = {"ZENOH_CONFIG_OVERRIDE": 'mode="peer";queries_default_timeout=1234'}
    config = cfg.session_config("tcp/127.0.0.1:1", env=env)
    assert get(config, "mode") == "peer"
    assert get(config, "queries_default_timeout") == 1234
    # The explicit router (the CLI's --router) beats the environment ...
    env2 = {"ZENOH_CONFIG_OVERRIDE": 'connect/endpoints=["tcp/127.0.0.1:2"]'}
    assert get(cfg.session_config("tcp/127.0.0.1:1", env=env2), "connect/endpoints") == [
        "tcp/127.0.0.1:1"
    ]
    # ... while the override beats ROS2LITE_ROUTER.
    env2["ROS2LITE_ROUTER"] = "tcp/127.0.0.1:3"
    assert get(cfg.session_config(env=env2), "connect/endpoints") == ["tcp/127.0.0.1:2"]
    admin = {"ZENOH_CONFIG_OVERRIDE": "adminspace/enabled=false"}
    router = cfg.router_config("tcp/127.0.0.1:5", env=admin)
    assert get(router, "adminspace/enabled") is False
    # a node's mode is a default too: the override wins
    forced = cfg.session_config(env={"ZENOH_CONFIG_OVERRIDE": 'mode="client"'}, mode="peer")
    assert get(forced, "mode") == "client"
    with pytest.raises(ConfigError, match="ZENOH_CONFIG_OVERRIDE: cannot set bogus/key=1"):
        cfg.session_config(env={"ZENOH_CONFIG_OVERRIDE": "bogus/key=1"})
    with pytest.raises(ConfigError, match="unknown variant"):
        cfg.session_config(env={"ZENOH_CONFIG_OVERRIDE": 'mode="sometimes"'})


def test_session_config_file_replaces_defaults(tmp_path: Path) -> None:
    path = tmp_path / "session.json5"
    path.write_text(
        '{ mode: "peer", connect: { endpoints: ["tcp/127.0.0.1:4242"] },'
        ' queries_default_timeout: 4321 }'
    )
    config = cfg.session_config(env={"ZENOH_SESSION_CONFIG_URI": str(path)})
    assert get(config, "mode") == "peer"
    assert get(config, "queries_default_timeout") == 4321
    assert get(config, "connect/endpoints") == ["tcp/127.0.0.1:4242"]
    assert get(config, "timestamping/enabled") is None  # our defaults are not mixed in
    explicit = cfg.session_config("tcp/127.0.0.1:1", env={"ZENOH_SESSION_CONFIG_URI": str(path)})
    assert get(explicit, "connect/endpoints") == ["tcp/127.0.0.1:1"]
    with pytest.raises(ConfigError, match="not a readable file"):
        cfg.session_config(env={"ZENOH_SESSION_CONFIG_URI": str(tmp_path / "missing.json5")})
    bad = tmp_path / "bad.json5"
    bad.write_text("{ mode: ")
    with pytest.raises(ConfigError, match="ZENOH_SESSION_CONFIG_URI"):
        cfg.session_config(env={"ZENOH_SESSION_CONFIG_URI": str(bad)})


RMW_ZENOH_SESSION = """{
  mode: "peer",
  connect: { endpoints: %s },
  listen: { endpoints: ["tcp/localhost:0"] },
  scouting: { multicast: { enabled: %s }, gossip: { enabled: true } },
}"""


def test_a_tool_opens_a_nodes_peer_file_as_a_client(tmp_path: Path) -> None:
    """rmw_zenoh's session file (peer, a router to connect to, no multicast): a tool
    (mode="client") opens it as a client of that router, a node keeps peer; a file for
    router-less peers, and a mode the override sets, are left alone."""
    path = tmp_path / "session.json5"
    path.write_text(RMW_ZENOH_SESSION % ('["tcp/localhost:7447"]', "false"))
    env = {"ZENOH_SESSION_CONFIG_URI": str(path)}
    tool = cfg.session_config(env=env)
    assert get(tool, "mode") == "client"
    assert get(tool, "connect/endpoints") == ["tcp/localhost:7447"]
    assert get(cfg.session_config(env=env, mode="peer"), "mode") == "peer"
    forced = cfg.session_config(env={**env, "ZENOH_CONFIG_OVERRIDE": 'mode="peer"'})
    assert get(forced, "mode") == "peer"
    path.write_text(RMW_ZENOH_SESSION % ('{ peer: ["tcp/localhost:7447"] }', "false"))
    per_mode = cfg.session_config(env=env)
    assert get(per_mode, "mode") == "client"
    assert get(per_mode, "connect/endpoints")["client"] == ["tcp/localhost:7447"]
    path.write_text(RMW_ZENOH_SESSION % ("[]", "false"))
    assert get(cfg.session_config(env=env), "mode") == "peer"
    path.write_text(RMW_ZENOH_SESSION % ('["tcp/localhost:7447"]', "true"))
    assert get(cfg.session_config(env=env), "mode") == "peer"


def test_router_config(tmp_path: Path) -> None:
    config = cfg.router_config("tcp/127.0.0.1:5555", connect=["tcp/10.0.0.1:7447"], env={})
    assert get(config, "mode") == "router"
    assert get(config, "listen/endpoints") == ["tcp/127.0.0.1:5555"]
    assert get(config, "connect/endpoints") == ["tcp/10.0.0.1:7447"]
    assert get(config, "scouting/multicast/enabled") is False
    assert get(config, "timestamping/enabled") is True
    wide = cfg.router_config("tcp/127.0.0.1:5555", listen=["tcp/0.0.0.0:5555"], env={})
    assert get(wide, "listen/endpoints") == ["tcp/0.0.0.0:5555"]
    default = cfg.router_config(env={})
    assert get(default, "listen/endpoints") == ["tcp/127.0.0.1:7447"]  # loopback only
    path = tmp_path / "router.json5"
    path.write_text('{ mode: "router", listen: { endpoints: ["tcp/127.0.0.1:6000"] } }')
    from_file = cfg.router_config(env={"ZENOH_ROUTER_CONFIG_URI": str(path)})
    assert get(from_file, "listen/endpoints") == ["tcp/127.0.0.1:6000"]


def test_open_session_fails_fast_without_router(private_domain: int, dead_endpoint: str) -> None:
    start = time.monotonic()
    with pytest.raises(RouterUnavailableError) as err:
        open_session(dead_endpoint)
    assert time.monotonic() - start < 3.0
    assert str(err.value) == (
        f"No Zenoh router answers at {dead_endpoint} (start one with 'ros2lite daemon start')"
    )
    assert err.value.endpoint == dead_endpoint


def test_open_session_fails_fast_in_peer_mode(
    private_domain: int, dead_endpoint: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    # A peer would happily open with no router; we must still refuse quickly.
    monkeypatch.setenv("ZENOH_CONFIG_OVERRIDE", 'mode="peer";connect/exit_on_failure=false')
    start = time.monotonic()
    with pytest.raises(RouterUnavailableError, match=dead_endpoint):
        open_session(dead_endpoint)
    assert time.monotonic() - start < 3.0


@pytest.mark.parametrize("mode", ["client", "peer"])
def test_pub_sub_and_liveliness_through_router(
    live_router: str, private_domain: int, monkeypatch: pytest.MonkeyPatch, mode: str
) -> None:
    monkeypatch.setenv("ZENOH_CONFIG_OVERRIDE", f'mode="{mode}"')
    hash_ = "RIHS01_" + "0" * 64
    key = topic_key(cfg.domain_id(), "/chatter", "std_msgs/msg/String", hash_)
    a = open_session(live_router)
    b = open_session(live_router)
    try:
        got: list[bytes] = []
        arrived = threading.Event()

        def on_sample(sample: zenoh.Sample) -> None:
            got.append(sample.payload.to_bytes())
            arrived.set()

        sub = b.declare_subscriber(key, on_sample)
        token = a.liveliness().declare_token(
            node_token(private_domain, str(a.zid()), 0, "/", "talker")
        )
        deadline = time.monotonic() + 5
        while not arrived.is_set() and time.monotonic() < deadline:
            a.put(key, b"\x00\x01\x00\x00hello")
            arrived.wait(0.05)
        assert got and got[0] == b"\x00\x01\x00\x00hello"
        expected = [f"@ros2_lv/{private_domain}/{a.zid()}/0/0/NN/%/%/talker"]

        def tokens() -> list[str]:
            replies = b.liveliness().get(
                liveliness_subscription_key(private_domain),
                zenoh.handlers.FifoChannel(1024),
                timeout=2,
            )
            return [str(r.ok.key_expr) for r in replies if r.ok is not None]

        # the token reaches the router on its own way, after the samples: ask until it is there
        # (a loaded machine saw an empty first answer): exactly this token, within a bound
        wait_until(lambda: tokens() == expected, timeout=10, interval=0.1)
        token.undeclare()
        sub.undeclare()
    finally:
        a.close()
        b.close()
