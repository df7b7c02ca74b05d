"""The daemon's graph cache: what tools read instead of joining the graph."""

from __future__ import annotations

import contextlib
import os
import signal
import socket
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from ros2lite import daemon
from ros2lite.daemon.graph_cache import cache_endpoint, cached_keys
from ros2lite.daemon.paths import graph_socket, log_file
from ros2lite.qos import QoSProfile
from ros2lite.transport.keys import EntityKind, endpoint_token, node_token
from ros2lite.transport.open import open_session
from tests.spinning import wait_until

DOMAIN = 231  # the daemon fixtures' ROS_DOMAIN_ID
HASH = 'RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18'


class Tokens:
    """A peer session on the daemon's router declaring a node and one publisher."""

    def __init__(self, endpoint: str, domain: int, topic: str) -> None:
        self.session = open_session(endpoint, mode='peer')
        zid = str(self.session.info.zid())
        self.node = node_token(domain, zid, 0, '/', 'cached')
        self.publisher = endpoint_token(
            domain,
            zid,
            0,
            1,
            EntityKind.PUBLISHER,
            '/',
            'cached',
            topic,
            'std_msgs/msg/String',
            HASH,
            QoSProfile(depth=10),
        )
        lv = self.session.liveliness()
        self._tokens = [lv.declare_token(self.node), lv.declare_token(self.publisher)]

    def close(self) -> None:
        for token in self._tokens:
            token.undeclare()
        self.session.close()


@pytest.fixture
def running(endpoint: str) -> Iterator[str]:
    assert daemon.start(endpoint).started
    yield endpoint
    daemon.stop(endpoint)


def _cli(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, '-m', 'ros2lite', *args], capture_output=True, text=True, timeout=60
    )


def test_tokens_come_and_go_by_domain(running: str) -> None:
    tokens = Tokens(running, DOMAIN, '/cached_chatter')
    other = Tokens(running, DOMAIN - 1, '/elsewhere')
    try:
        keys = wait_until(lambda: (k := cached_keys(running, DOMAIN)) and len(k) == 2 and k)
        assert sorted(keys) == sorted([tokens.node, tokens.publisher])
        elsewhere = wait_until(
            lambda: (k := cached_keys(running, DOMAIN - 1)) and len(k) == 2 and k
        )
        assert sorted(elsewhere) == sorted([other.node, other.publisher])
        assert cached_keys(running, 7) == []
    finally:
        tokens.close()
        other.close()
    wait_until(lambda: cached_keys(running, DOMAIN) == [])


def test_topic_list_reads_the_cache_without_zenoh(
    running: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv('ROS2LITE_ROUTER', running)
    tokens = Tokens(running, DOMAIN, '/cached_chatter')
    try:
        wait_until(lambda: len(cached_keys(running, DOMAIN) or ()) == 2)
        # -X importtime lists every module the run imported: the graph came with no zenoh
        run = subprocess.run(
            [sys.executable, '-X', 'importtime', '-m', 'ros2lite', 'topic', 'list', '-t'],
            capture_output=True,
            text=True,
            timeout=60,
        )
        assert run.returncode == 0, run.stderr
        assert '/cached_chatter [std_msgs/msg/String]' in run.stdout.splitlines()
        assert ' zenoh' not in run.stderr and 'ros2lite.transport.session' not in run.stderr
        # --no-daemon asks the router itself: the same answer
        direct = _cli('topic', 'list', '-t', '--no-daemon')
        assert direct.returncode == 0, direct.stderr
        assert '/cached_chatter [std_msgs/msg/String]' in direct.stdout.splitlines()
        nodes = _cli('node', 'list')
        assert nodes.stdout.splitlines() == ['/cached']
    finally:
        tokens.close()


def test_a_dead_daemons_socket_is_not_believed(
    running: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv('ROS2LITE_ROUTER', running)
    info = daemon.status(running).info
    assert info is not None
    os.kill(info.pid, signal.SIGKILL)
    wait_until(lambda: not daemon.status(running).running)
    assert graph_socket(running).exists()  # left behind by SIGKILL
    assert cached_keys(running, DOMAIN) is None
    # the verb falls back: it starts a new daemon and asks its router
    run = _cli('topic', 'list')
    assert run.returncode == 0, run.stderr
    assert daemon.status(running).running
    assert cached_keys(running, DOMAIN) is not None  # the new daemon serves again


def test_bad_requests_get_nothing_and_break_nothing(running: str) -> None:
    for request in (b'graph x\n', b'\xff' * 80, b'rm -rf /\n', b''):
        with socket.socket(socket.AF_UNIX) as sock:
            sock.settimeout(5)
            sock.connect(str(graph_socket(running)))
            sock.sendall(request)
            sock.shutdown(socket.SHUT_WR)
            # closed without a word (reset when an overlong request was left unread)
            with contextlib.suppress(ConnectionResetError):
                assert sock.recv(100) == b''
    assert cached_keys(running, DOMAIN) == []


def test_a_long_runtime_dir_still_serves(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    from tests.spinning import free_port

    deep = tmp_path / ('d' * 60) / ('e' * 60)
    deep.mkdir(parents=True, mode=0o700)
    monkeypatch.setenv('XDG_RUNTIME_DIR', str(deep))
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    assert len(str(graph_socket(endpoint))) > 108  # too long for a socket address
    assert daemon.start(endpoint).started
    try:
        assert graph_socket(endpoint).exists()
        assert cached_keys(endpoint, DOMAIN) == []
    finally:
        daemon.stop(endpoint)
    assert not graph_socket(endpoint).exists()


@pytest.mark.parametrize(
    'var, value',
    [
        ('ZENOH_CONFIG_OVERRIDE', 'mode="client"'),
        ('ZENOH_SESSION_CONFIG_URI', '/etc/zenoh.json5'),
        ('ROS_SECURITY_ENABLE', 'true'),
    ],
)
def test_no_cache_for_a_session_the_user_configured(
    monkeypatch: pytest.MonkeyPatch, runtime: Path, var: str, value: str
) -> None:
    monkeypatch.setenv('ROS2LITE_ROUTER', 'tcp/127.0.0.1:7447')
    assert cache_endpoint() == 'tcp/127.0.0.1:7447'
    monkeypatch.setenv(var, value)
    assert cache_endpoint() is None


def test_a_token_with_a_strange_domain_is_ignored(running: str) -> None:
    # '²' passes str.isdigit() but not int(): the daemon's callback must not trip on it
    session = open_session(running, mode='peer')
    try:
        token = session.liveliness().declare_token('@ros2_lv/²/zid/0/0/NN/%/%/odd')
        tokens = Tokens(running, DOMAIN, '/after_odd')
        try:
            wait_until(lambda: len(cached_keys(running, DOMAIN) or ()) == 2)
        finally:
            tokens.close()
            token.undeclare()
    finally:
        session.close()
    assert daemon.status(running).running
    log = log_file(running).read_text()
    assert 'Traceback' not in log and 'ValueError' not in log, log


def test_a_token_flood_is_bounded_counted_and_said(
    ros_router: str,
    tmp_path: Path,
    monkeypatch: pytest.MonkeyPatch,
    capfd: pytest.CaptureFixture[str],
) -> None:
    """R-G18/G16: past its limit the cache keeps no more tokens; it counts the dropped ones,
    says so in the daemon's log, and answers 'incomplete' for a domain while any of its
    dropped tokens lives (tools then ask the router); other domains are served as before."""
    from ros2lite.daemon.graph_cache import GraphServer, cache_stats

    monkeypatch.setenv('XDG_RUNTIME_DIR', str(tmp_path))
    flood, calm = 201, 202
    server_session = open_session(ros_router, mode='client')
    server = GraphServer(server_session, graph_socket(ros_router), limit=100)
    client = open_session(ros_router, mode='client')
    try:
        lv = client.liveliness()
        calm_key = f'@ros2_lv/{calm}/{"c" * 32}/0/0/NN/%/%/calm'
        calm_token = lv.declare_token(calm_key)
        wait_until(lambda: cached_keys(ros_router, calm) is not None and server.kept == 1)
        flood_tokens = [
            lv.declare_token(f'@ros2_lv/{flood}/{"f" * 32}/0/{i}/NN/%/%/flood{i}')
            for i in range(150)
        ]
        wait_until(lambda: server.kept + server.dropped == 151, timeout=20)
        assert (server.kept, server.dropped) == (100, 51)
        assert cached_keys(ros_router, flood) is None  # incomplete: tools ask the router
        assert cached_keys(ros_router, calm) == [calm_key]  # another domain: served
        assert cache_stats(ros_router) == {'kept': 100, 'dropped': 51, 'limit': 100}
        for token in flood_tokens:
            token.undeclare()
        wait_until(lambda: cached_keys(ros_router, flood) == [], timeout=20)
        assert server.kept == 1
        calm_token.undeclare()
    finally:
        server.close()
        client.close()
        server_session.close()
    log = capfd.readouterr().err
    assert 'ros2lite daemon: graph cache full (100 tokens): 1 token(s) not kept so far' in log
    assert log.count('graph cache full') == 6, log  # at 1, 2, 4, … 32: said, never flooding


# a publisher token whose deadline (99,999,999,999 s) is past what a Duration holds: rmw_zenoh
# reads any uint64 there, so its peers may well announce one
def _odd_tokens(zid: str, domain: int) -> tuple[str, str]:
    overflow = (
        f'@ros2_lv/{domain}/{zid}/5/7/MP/%/%/odd_node/%odd_topic/std_msgs::msg::dds_::String_/'
        f'{HASH}/::,10:99999999999,:,:,,'
    )
    # one key holding a newline and what looks like a second node's token after it
    forged = f'@ros2_lv/{domain}/{zid}/6/8/NN/%/%/nl\n@ros2_lv/{domain}/{zid}/7/9/NN/%/%/forged'
    return overflow, forged


@pytest.mark.parametrize('no_daemon', [False, True])
def test_odd_tokens_are_skipped_or_clamped_and_said_once(
    running: str, monkeypatch: pytest.MonkeyPatch, no_daemon: bool
) -> None:
    monkeypatch.setenv('ROS2LITE_ROUTER', running)
    tokens = Tokens(running, DOMAIN, '/cached_chatter')
    overflow, forged = _odd_tokens(str(tokens.session.info.zid()), DOMAIN)
    lv = tokens.session.liveliness()
    odd = [lv.declare_token(overflow), lv.declare_token(forged)]
    flag = ['--no-daemon'] if no_daemon else []
    try:
        wait_until(lambda: len(cached_keys(running, DOMAIN) or ()) == 4)
        topics = _cli('topic', 'list', '-t', *flag)
        assert topics.returncode == 0, topics.stderr
        # the overflowing deadline is infinite: the topic is listed with the rest
        assert topics.stdout.splitlines() == [
            '/cached_chatter [std_msgs/msg/String]',
            '/odd_topic [std_msgs/msg/String]',
        ], topics.stdout
        nodes = _cli('node', 'list', *flag)
        assert nodes.returncode == 0, nodes.stderr
        # the newline token is skipped, never read as two nodes; the others are listed (a
        # node known only by its endpoints' tokens too, as rmw_zenoh's graph lists it)
        assert nodes.stdout.splitlines() == ['/cached', '/odd_node'], nodes.stdout
        said = [line for line in nodes.stderr.splitlines() if 'skipped' in line]
        assert len(said) == 1, nodes.stderr
        assert said[0].startswith('ros2lite: skipped 1 liveliness token(s)'), said
        assert 'forged' in said[0] and '\\n' in said[0]  # the key shown, escaped
        info = _cli('topic', 'info', '/odd_topic', '-v', *flag)
        assert info.returncode == 0, info.stderr
        assert '  Deadline: Infinite' in info.stdout.splitlines(), info.stdout
    finally:
        for token in odd:
            token.undeclare()
        tokens.close()
