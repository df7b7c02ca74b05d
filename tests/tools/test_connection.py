"""A spinning tool says when its router link drops and when it is back (R-F2): `topic echo`
on a client session lost ~6000 messages of a router outage without a word."""

from __future__ import annotations

import os
import random
import subprocess
import sys
from collections.abc import Iterator
from typing import Any

import pytest

from tests.spinning import free_port, wait_until
from tests.transport.test_security import Lines


def _router(endpoint: str) -> Any:
    import zenoh

    from ros2lite.transport.config import router_config

    return zenoh.open(router_config(endpoint, env={}))


@pytest.fixture
def echo_env() -> Iterator[dict[str, str]]:
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    env = {k: v for k, v in os.environ.items() if not k.startswith(('ROS_SECURITY', 'ZENOH_'))}
    env.update(
        ROS2LITE_ROUTER=endpoint,
        ROS2LITE_NO_DAEMON='1',
        ROS_DOMAIN_ID=str(random.randint(100, 232)),
    )
    yield env


def test_echo_says_when_the_router_goes_and_comes_back(echo_env: dict[str, str]) -> None:
    endpoint = echo_env['ROS2LITE_ROUTER']
    router = _router(endpoint)
    procs: list[subprocess.Popen[str]] = []

    def start(*args: str) -> Lines:
        proc = subprocess.Popen(
            [sys.executable, '-m', 'ros2lite', *args],
            env=echo_env,
            text=True,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
        )
        procs.append(proc)
        return Lines(proc)

    try:
        echo = start('topic', 'echo', '/link_watch', 'std_msgs/msg/String')
        start('topic', 'pub', '-r', '20', '/link_watch', 'std_msgs/msg/String', '{data: tick}')
        echo.wait_for('data: tick')
        router.close()
        lost = echo.wait_for('Lost the link to the Zenoh router', timeout=10)
        assert f'at {endpoint}: what is published until it is back' in lost
        router = _router(endpoint)
        echo.wait_for(f'The link to the Zenoh router at {endpoint} is back', timeout=15)
        lines = echo.text().splitlines()
        back = next(i for i, line in enumerate(lines) if 'is back' in line)
        start('topic', 'pub', '-r', '20', '/link_watch', 'std_msgs/msg/String', '{data: again}')
        wait_until(lambda: 'data: again' in echo.text(), timeout=15)
        assert back < echo.text().splitlines().index('data: again')
        assert echo.text().count('Lost the link') == 1
    finally:
        for proc in procs:
            proc.terminate()
            try:
                proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                proc.kill()
        router.close()


def test_a_graph_answer_cut_by_its_time_out_is_said_once(
    alien_session: Any, ros_router: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    """R5-G3: `--no-daemon` with 20k tokens returned about half in silence; an answer the
    time-out ends is now said to be incomplete, once, and a whole answer says nothing."""
    from ros2lite.tools.connection import Connection

    domain = random.randint(1, 99)
    monkeypatch.setenv('ROS_DOMAIN_ID', str(domain))
    zid = os.urandom(16).hex()
    lv = alien_session.liveliness()
    tokens = [lv.declare_token(f'@ros2_lv/{domain}/{zid}/{i}/{i}/NN/%/%/n{i}') for i in range(3000)]
    try:
        notes: list[str] = []
        with Connection(graph_cache=False, on_note=notes.append) as conn:
            assert wait_until(lambda: len(conn.entities(timeout=10.0)) == 3000, timeout=60)
            assert notes == []  # a whole answer is not doubted
            cut = conn.entities(timeout=0.005)
            conn.entities(timeout=0.005)
        assert len(cut) < 3000
        assert len(notes) == 1, notes
        assert notes[0].startswith("the graph may be incomplete: the router's answer was cut")
    finally:
        for token in tokens:
            token.undeclare()
