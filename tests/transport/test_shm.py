"""Shared memory as rmw_zenoh switches it: the settings, a payload that really crosses in a
segment, the bytes reaching a peer with it off (both ways, through the router to `topic
echo`), and a subscriber that keeps every sample pinning no more than the pool."""

from __future__ import annotations

import os
from collections.abc import Iterator
from typing import Any

import pytest

from ros2lite.transport.shm import (
    DEFAULT_ALLOC_SIZE,
    DEFAULT_THRESHOLD,
    register,
    shm_publisher,
    shm_settings,
)
from tests.conftest import Processes
from tests.spinning import free_port, wait_until

ON = 'transport/shared_memory/enabled=true'
TRANSPORT_POOL = 4 << 20


def _config(enabled: bool | None) -> Any:
    import zenoh

    config = zenoh.Config()
    if enabled is not None:
        config.insert_json5('transport/shared_memory/enabled', 'true' if enabled else 'false')
    return config


def test_settings_follow_the_config_key_and_rmw_zenohs_variables() -> None:
    assert not shm_settings(_config(False), {}).enabled
    on = shm_settings(_config(True), {})
    assert (on.enabled, on.alloc_size, on.threshold) == (
        True,
        DEFAULT_ALLOC_SIZE,
        DEFAULT_THRESHOLD,
    )
    env = {'ZENOH_SHM_ALLOC_SIZE': str(8 << 20), 'ZENOH_SHM_MESSAGE_SIZE_THRESHOLD': '4096'}
    sized = shm_settings(_config(True), env)
    assert (sized.alloc_size, sized.threshold) == (8 << 20, 4096)
    # not a power of two, or not a number: the default stays
    bad = {'ZENOH_SHM_ALLOC_SIZE': 'lots', 'ZENOH_SHM_MESSAGE_SIZE_THRESHOLD': '3000'}
    kept = shm_settings(_config(True), bad)
    assert (kept.alloc_size, kept.threshold) == (DEFAULT_ALLOC_SIZE, DEFAULT_THRESHOLD)
    # Humble's rmw_zenoh publishes nothing through shared memory
    assert not shm_settings(_config(True), {'ROS_DISTRO': 'humble'}).enabled


def test_our_session_configs_keep_it_off_unless_overridden() -> None:
    from ros2lite.transport.config import session_config

    off = session_config(f'tcp/127.0.0.1:{free_port()}', {}, mode='peer')
    assert not shm_settings(off, {}).enabled
    on = session_config(f'tcp/127.0.0.1:{free_port()}', {'ZENOH_CONFIG_OVERRIDE': ON}, mode='peer')
    assert shm_settings(on, {}).enabled


@pytest.fixture
def linked_pair() -> Iterator[tuple[Any, Any]]:
    """Two peer sessions with shared memory on, the second connected to the first's port."""
    import zenoh

    port = free_port()
    sessions = []
    for listen, connect in (
        (f'["tcp/127.0.0.1:{port}"]', '[]'),
        ('[]', f'["tcp/127.0.0.1:{port}"]'),
    ):
        config = _config(True)
        for key, value in (
            ('mode', '"peer"'),
            ('listen/endpoints', listen),
            ('connect/endpoints', connect),
            ('scouting/multicast/enabled', 'false'),
            # Zenoh's own pool, into which it moves other large payloads of a shm link
            ('transport/shared_memory/transport_optimization/pool_size', str(TRANSPORT_POOL)),
        ):
            config.insert_json5(key, value)
        sessions.append(zenoh.open(config))
    try:
        yield sessions[0], sessions[1]
    finally:
        for session in sessions:
            session.close()


def test_large_payloads_cross_in_a_segment_small_ones_do_not(linked_pair: Any) -> None:
    import zenoh

    sender, receiver = linked_pair
    register(sender, shm_settings(_config(True), {'ZENOH_SHM_ALLOC_SIZE': str(4 << 20)}))
    got: list[Any] = []
    sub = receiver.declare_subscriber('shm/t', got.append)
    plain = sender.declare_publisher('shm/t')
    pub = shm_publisher(sender, plain.put, plain.undeclare)
    assert pub is not None
    big, small = bytes(range(256)) * 4096, b'x' * (DEFAULT_THRESHOLD - 1)

    def sent_both() -> bool:
        pub.put(big, attachment=b'a')
        pub.put(small)
        return len(got) >= 2

    wait_until(sent_both)
    bigs = [s for s in got if len(s.payload) == len(big)]
    smalls = [s for s in got if len(s.payload) == len(small)]
    assert bigs and smalls
    assert bigs[0].payload.as_shm() is not None and bigs[0].payload.to_bytes() == big
    assert bigs[0].attachment.to_bytes() == b'a'
    assert smalls[0].payload.as_shm() is None
    sub.undeclare()
    pub.undeclare()
    assert isinstance(got[0].payload, zenoh.ZBytes)


def test_a_subscriber_that_keeps_every_sample_pins_at_most_the_pool(linked_pair: Any) -> None:
    import zenoh

    sender, receiver = linked_pair
    pool = 4 << 20
    register(sender, shm_settings(_config(True), {'ZENOH_SHM_ALLOC_SIZE': str(pool)}))
    kept: list[Any] = []
    sub = receiver.declare_subscriber('shm/keep', kept.append)
    plain = sender.declare_publisher(  # blocking: none may be dropped by congestion
        'shm/keep',
        reliability=zenoh.Reliability.RELIABLE,
        congestion_control=zenoh.CongestionControl.BLOCK,
    )
    wait_until(lambda: plain.matching_status.matching)
    pub = shm_publisher(sender, plain.put, plain.undeclare)
    assert pub is not None
    frame = bytes(1 << 20)
    for _ in range(16):  # twice what both pools hold, every one kept
        pub.put(frame)
    wait_until(lambda: len(kept) >= 16)
    in_segments = sum(len(s.payload) for s in kept if s.payload.as_shm() is not None)
    # ours and Zenoh's transport pool bound what is pinned; the rest came as plain bytes
    assert 0 < in_segments <= pool + TRANSPORT_POOL
    assert all(s.payload.to_bytes() == frame for s in kept)
    kept.clear()  # dropped samples give their chunks back: large frames use segments again

    def in_a_segment_again() -> bool:
        pub.put(frame)
        return bool(kept) and kept[-1].payload.as_shm() is not None

    wait_until(in_a_segment_again)
    sub.undeclare()
    pub.undeclare()


def _env(shm: bool) -> dict[str, str]:
    env = {**os.environ, 'ZENOH_SHM_MESSAGE_SIZE_THRESHOLD': '16'}
    if shm:
        env['ZENOH_CONFIG_OVERRIDE'] = ON
    else:
        env.pop('ZENOH_CONFIG_OVERRIDE', None)
    return env


@pytest.mark.parametrize('pub_shm', [True, False], ids=['shm-pub', 'shm-echo'])
def test_topic_echo_through_the_router_gets_the_bytes(processes: Processes, pub_shm: bool) -> None:
    text = 'through shared memory or not, the same bytes'
    topic = f'/shm_echo_{int(pub_shm)}'
    echo = processes.cli(
        'topic', 'echo', '--once', topic, 'std_msgs/msg/String', env=_env(not pub_shm)
    )
    processes.cli(
        'topic',
        'pub',
        '-r',
        '10',
        topic,
        'std_msgs/msg/String',
        f'{{data: "{text}"}}',
        env=_env(pub_shm),
    )
    out, err = echo.communicate(timeout=30)
    assert echo.returncode == 0, err
    assert f'data: {text}' in out


def test_a_context_opened_with_it_on_publishes_through_its_pool(
    ros_router: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    from ros2lite.context import Context
    from ros2lite.transport.session import declare_publisher
    from ros2lite.transport.shm import ShmPublisher, settings_of

    monkeypatch.setenv('ZENOH_CONFIG_OVERRIDE', ON)
    monkeypatch.setenv('ZENOH_SHM_ALLOC_SIZE', str(2 << 20))
    ctx = Context()
    ctx.init([])
    session = ctx.require()
    try:
        assert settings_of(session).alloc_size == 2 << 20
        from ros2lite.qos import QoSProfile

        pub = declare_publisher(session, 'shm/ctx', QoSProfile(depth=1))
        assert isinstance(pub, ShmPublisher)
        pub.put(bytes(1 << 20), attachment=bytes(33))
        pub.undeclare()
    finally:
        ctx.try_shutdown()
    assert not settings_of(session).enabled  # forgotten with its session


def test_the_hand_written_rmw_zenoh_peer_hears_a_publisher_with_it_on(
    ros_router: str, alien_session: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The alien peer of `tests/test_alien_peer.py` (keys spelled by hand) through the router
    (shm off): each sample arrives whole, attachment and all, as rmw_zenoh would send it."""
    import struct
    import threading

    from ros2lite.context import Context
    from ros2lite.node import Node
    from tests.test_alien_peer import STRING_HASH, STRING_TYPE, parse_cdr_string

    monkeypatch.setenv('ZENOH_CONFIG_OVERRIDE', ON)
    monkeypatch.setenv('ZENOH_SHM_MESSAGE_SIZE_THRESHOLD', '16')
    ctx = Context()
    ctx.init([])
    got: list[tuple[bytes, bytes]] = []
    cond = threading.Condition()

    def on_sample(sample: Any) -> None:
        with cond:
            got.append((sample.payload.to_bytes(), sample.attachment.to_bytes()))
            cond.notify_all()

    d = ctx.domain_id
    sub = alien_session.declare_subscriber(f'{d}/shm_alien/{STRING_TYPE}/{STRING_HASH}', on_sample)
    token = alien_session.liveliness().declare_token(
        f'@ros2_lv/{d}/{alien_session.info.zid()}/0/0/MS/%/%/alien_listener/%shm_alien/'
        f'{STRING_TYPE}/{STRING_HASH}/::,10:,:,:,,'
    )
    try:
        node = Node('shm_talker', context=ctx)
        pub = node.create_publisher('std_msgs/msg/String', 'shm_alien', 10)
        wait_until(lambda: pub.get_subscription_count() >= 1, timeout=15)
        text = 'a String long enough for the shared-memory threshold'

        def heard() -> bool:
            pub.publish(pub.msg_type(data=text))
            with cond:
                return cond.wait_for(lambda: bool(got), 0.2)

        wait_until(heard, timeout=15)
        payload, att = got[0]
        assert parse_cdr_string(payload) == text
        assert len(att) == 33 and struct.unpack_from('<B', att, 16) == (16,)
        assert att[17:] == pub.gid
    finally:
        token.undeclare()
        sub.undeclare()
        ctx.try_shutdown()
