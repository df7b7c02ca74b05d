"""A node whose session is a Zenoh client (secured nodes are, by design) says when its router
link drops and when it is back: what is published meanwhile is lost to it (R5-G5 measured
5,547 of 15,000 lost in silence across a 5 s outage). A peer node says nothing of it."""

from __future__ import annotations

import random
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.spinning import free_port, wait_until
from tests.transport.test_security import environ, procs, start_node

__all__ = ['procs']  # the fixture

LOST = 'Lost the link to the Zenoh router at'
BACK = 'is back;'


@pytest.fixture
def keystore(tmp_path: Path) -> Iterator[dict[str, str]]:
    from ros2lite.security.keystore import create_enclave, create_keystore

    keystore = tmp_path / 'ks'
    env = {'ROS_DOMAIN_ID': str(random.randint(100, 232))}
    create_keystore(keystore, env)
    create_enclave(keystore, '/link/talker', env)
    yield {
        **env,
        'ROS_SECURITY_ENABLE': 'true',
        'ROS_SECURITY_STRATEGY': 'Enforce',
        'ROS_SECURITY_KEYSTORE': str(keystore),
        'ROS2LITE_ROUTER': f'tls/127.0.0.1:{free_port()}',
    }


def _router(secure: dict[str, str]) -> Any:
    import zenoh

    from ros2lite.daemon.router import router_security
    from ros2lite.transport.config import router_config

    return zenoh.open(router_config(env=secure, security=router_security(secure)))


def test_a_secured_node_says_when_its_router_goes_and_comes_back(
    keystore: dict[str, str], procs: list[Any]
) -> None:
    router = _router(keystore)
    try:
        talker = start_node(procs, environ(keystore), 'talker', '/link/talker')
        talker.wait_for('Publishing:')
        router.close()
        lost = talker.wait_for(LOST)
        assert keystore['ROS2LITE_ROUTER'] in lost and 'Zenoh client' in lost
        published = talker.text().count('Publishing:')
        wait_until(lambda: talker.text().count('Publishing:') >= published + 2, timeout=10)
        router = _router(keystore)
        back = talker.wait_for(BACK, timeout=30)  # the session's retry backs off to 1 s
        assert keystore['ROS2LITE_ROUTER'] in back
        # and how many of its messages went nowhere meanwhile (the talker publishes at 1 Hz)
        lost_count = int(back.split('is back; ')[1].split()[0])
        assert lost_count >= 2 and 'reached no one' in back
        assert talker.text().count(LOST) == 1
    finally:
        router.close()


def test_a_peer_node_keeps_quiet(ros_router: str, procs: list[Any]) -> None:
    import zenoh

    from ros2lite.transport.config import router_config

    endpoint = f'tcp/127.0.0.1:{free_port()}'
    router = zenoh.open(router_config(endpoint, env={}))
    talker = start_node(procs, environ({'ROS2LITE_ROUTER': endpoint}), 'talker', '/')
    talker.wait_for('Publishing:')
    router.close()
    published = talker.text().count('Publishing:')
    # two more seconds of publishing to the peers it has, eight looks at its router link
    assert wait_until(lambda: talker.text().count('Publishing:') >= published + 2, timeout=10)
    procs[-1].terminate()
    procs[-1].wait(timeout=10)
    assert LOST not in talker.text()
