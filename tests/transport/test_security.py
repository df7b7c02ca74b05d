"""A secured graph end to end: a real router with TLS (mutual authentication) and access
control made from a temporary sros2 keystore, real node and CLI processes around it.

What must hold (issue 16): secured talker → listener works; a process without a certificate
(or with one from another CA) cannot list, publish into or echo the graph; an enclave whose
permissions lack /chatter neither publishes it nor receives it; Enforce without material, or
with a tcp/ endpoint, refuses in one line; Permissive without material runs unsecured and
says so once.
"""

from __future__ import annotations

import os
import queue
import random
import subprocess
import sys
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.spinning import free_port

RESTRICTED_POLICY = """<policy version="0.2.0">
  <enclaves>
    <enclave path="/sec/restricted">
      <profiles>
        <profile ns="/" node="restricted">
          <topics publish="ALLOW" subscribe="ALLOW">
            <topic>other</topic>
          </topics>
        </profile>
      </profiles>
    </enclave>
  </enclaves>
</policy>
"""


class Lines:
    """A process's stderr+stdout, read line by line in the background, to wait on."""

    def __init__(self, proc: subprocess.Popen[str]) -> None:
        self.proc = proc
        self.lines: list[str] = []
        self._queue: queue.Queue[str] = queue.Queue()
        for stream in (proc.stdout, proc.stderr):
            threading.Thread(target=self._pump, args=(stream,), daemon=True).start()

    def _pump(self, stream: Any) -> None:
        for line in stream:
            self._queue.put(line.rstrip('\n'))

    def _drain(self) -> None:
        while not self._queue.empty():
            self.lines.append(self._queue.get_nowait())

    def wait_for(self, text: str, timeout: float = 20.0) -> str:
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            self._drain()
            for line in self.lines:
                if text in line:
                    return line
            time.sleep(0.05)
        self._drain()
        raise AssertionError(f'{text!r} not seen within {timeout} s: {self.lines[-10:]}')

    def text(self) -> str:
        self._drain()
        return '\n'.join(self.lines)


@pytest.fixture(scope='module')
def secured(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, str]]:
    """A keystore (talker, listener, restricted enclaves) and a secured router; yields the
    environment a secured process runs with."""
    import zenoh

    from ros2lite.daemon.router import router_security
    from ros2lite.security.keystore import create_enclave, create_keystore, create_permission
    from ros2lite.transport.config import router_config

    keystore = tmp_path_factory.mktemp('keystore') / 'ks'
    domain = str(random.randint(100, 232))
    env = {'ROS_DOMAIN_ID': domain}
    create_keystore(keystore, env)
    for name in ('/sec/talker', '/sec/listener', '/sec/restricted'):
        create_enclave(keystore, name, env)
    policy = keystore.parent / 'restricted.xml'
    policy.write_text(RESTRICTED_POLICY)
    create_permission(keystore, '/sec/restricted', policy, env)
    endpoint = f'tls/127.0.0.1:{free_port()}'
    secure = {
        **env,
        'ROS_SECURITY_ENABLE': 'true',
        'ROS_SECURITY_STRATEGY': 'Enforce',
        'ROS_SECURITY_KEYSTORE': str(keystore),
        'ROS2LITE_ROUTER': endpoint,
    }
    router = zenoh.open(router_config(env=secure, security=router_security(secure)))
    try:
        yield secure
    finally:
        router.close()


def environ(extra: dict[str, str], drop: tuple[str, ...] = ()) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith(('ROS_SECURITY', 'ZENOH_'))}
    env.update(extra, ROS2LITE_NO_DAEMON='1')
    for key in drop:
        env.pop(key, None)
    return env


def start_cli(args: list[str], env: dict[str, str]) -> tuple[subprocess.Popen[str], Lines]:
    proc = subprocess.Popen(
        [sys.executable, '-m', 'ros2lite', *args],
        env=env,
        text=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    return proc, Lines(proc)


def run_cli(
    args: list[str], env: dict[str, str], timeout: float = 30
) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, '-m', 'ros2lite', *args],
        env=env,
        text=True,
        capture_output=True,
        timeout=timeout,
    )


@pytest.fixture
def procs() -> Iterator[list[subprocess.Popen[str]]]:
    started: list[subprocess.Popen[str]] = []
    try:
        yield started
    finally:
        for proc in started:
            if proc.poll() is None:
                proc.terminate()
            try:
                proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()


def start_node(procs: list[Any], env: dict[str, str], exe: str, enclave: str) -> Lines:
    proc, lines = start_cli(['run', 'demo_nodes_py', exe, '--ros-args', '--enclave', enclave], env)
    procs.append(proc)
    return lines


def test_secured_talker_to_listener(secured: dict[str, str], procs: list[Any]) -> None:
    env = environ(secured)
    listener = start_node(procs, env, 'listener', '/sec/listener')
    start_node(procs, env, 'talker', '/sec/talker')
    listener.wait_for('I heard: [Hello World:')
    # a CLI verb with its own enclave sees the secured graph (and the enclaves of the nodes)
    verb = run_cli(['node', 'list'], {**env, 'ROS_SECURITY_ENCLAVE_OVERRIDE': '/sec/listener'})
    assert verb.returncode == 0, verb.stderr
    assert {'/talker', '/listener'} <= set(verb.stdout.split()), verb.stdout


@pytest.mark.parametrize(
    'verb',
    [
        ['topic', 'list'],
        ['topic', 'echo', '/chatter', 'std_msgs/msg/String'],
        ['topic', 'pub', '--times', '1', '/chatter', 'std_msgs/msg/String'],
    ],
)
def test_unsecured_process_is_refused(secured: dict[str, str], verb: list[str]) -> None:
    """No certificate at all: the TLS handshake fails, the verb says so in one line."""
    env = environ({'ROS2LITE_ROUTER': secured['ROS2LITE_ROUTER']})
    result = run_cli(verb, env)
    assert result.returncode == 1
    assert result.stderr.strip().count('\n') == 0 and 'Traceback' not in result.stderr
    assert 'refused the TLS handshake' in result.stderr, result.stderr
    # nor through the same port in plain TCP
    port = secured['ROS2LITE_ROUTER'].rpartition(':')[2]
    plain = run_cli(verb, environ({'ROS2LITE_ROUTER': f'tcp/127.0.0.1:{port}'}))
    assert plain.returncode == 1 and 'Traceback' not in plain.stderr


def test_foreign_keystore_is_refused(secured: dict[str, str], tmp_path: Path) -> None:
    """A certificate from another CA, even for an enclave name the router knows: the node
    does not start, the verb does not publish; each says why in one line."""
    from ros2lite.security.keystore import create_enclave, create_keystore

    other = tmp_path / 'other'
    create_keystore(other, secured)
    create_enclave(other, '/sec/talker', secured)
    env = environ({**secured, 'ROS_SECURITY_KEYSTORE': str(other)})
    node = run_cli(
        ['run', 'demo_nodes_py', 'talker', '--ros-args', '--enclave', '/sec/talker'], env
    )
    assert node.returncode != 0
    assert node.stderr.splitlines()[0].startswith('the router at tls/'), node.stderr
    assert 'refused the TLS handshake' in node.stderr and 'Traceback' not in node.stderr
    verb = run_cli(
        ['topic', 'pub', '--times', '1', '/chatter', 'std_msgs/msg/String'],
        {**env, 'ROS_SECURITY_ENCLAVE_OVERRIDE': '/sec/talker'},
    )
    assert verb.returncode == 1 and 'refused the TLS handshake' in verb.stderr, verb.stderr


def test_enclave_without_chatter_permission(secured: dict[str, str], procs: list[Any]) -> None:
    env = environ(secured)
    listener = start_node(procs, env, 'listener', '/sec/listener')
    restricted = environ({**secured, 'ROS_SECURITY_ENCLAVE_OVERRIDE': '/sec/restricted'})
    # its publications never arrive …
    pub_proc, _ = start_cli(
        ['topic', 'pub', '-r', '20', '/chatter', 'std_msgs/msg/String', '{data: from-restricted}'],
        restricted,
    )
    procs.append(pub_proc)
    # … while an allowed enclave's do, through the same router, at the same time
    allowed = environ({**secured, 'ROS_SECURITY_ENCLAVE_OVERRIDE': '/sec/talker'})
    ok_proc, _ = start_cli(
        ['topic', 'pub', '-r', '20', '/chatter', 'std_msgs/msg/String', '{data: from-talker}'],
        allowed,
    )
    procs.append(ok_proc)
    listener.wait_for('I heard: [from-talker]')
    # its echo receives nothing, while the listener enclave's echo of the same talker does
    echo_denied, denied_lines = start_cli(
        ['topic', 'echo', '/chatter', 'std_msgs/msg/String'], restricted
    )
    procs.append(echo_denied)
    echo_ok, ok_lines = start_cli(
        ['topic', 'echo', '/chatter', 'std_msgs/msg/String'],
        environ({**secured, 'ROS_SECURITY_ENCLAVE_OVERRIDE': '/sec/listener'}),
    )
    procs.append(echo_ok)
    ok_lines.wait_for('data: from-talker')
    listener.wait_for('I heard: [from-talker]')
    time.sleep(1.0)  # a window in which ~20 allowed samples flowed past both echoes
    assert 'from-restricted' not in listener.text()
    assert 'data:' not in denied_lines.text(), denied_lines.text()
    assert echo_denied.poll() is None  # it runs: connected, authenticated, yet told nothing


def test_enforce_without_material_refuses(secured: dict[str, str]) -> None:
    env = environ(secured)
    result = run_cli(
        ['run', 'demo_nodes_py', 'talker', '--ros-args', '--enclave', '/sec/nobody'], env
    )
    assert result.returncode != 0
    lines = [line for line in result.stderr.splitlines() if line.strip()]
    # the node's one line, then `run`'s own (as ros2 run says it)
    assert lines[1:] == ['[ros2run]: Process exited with failure 1'], result.stderr
    assert lines[0].startswith(
        'SECURITY ERROR: unable to find a folder matching the name \'/sec/nobody\''
    ), lines


def test_enforce_refuses_tcp_endpoint(secured: dict[str, str]) -> None:
    env = environ(
        {
            **secured,
            'ROS2LITE_ROUTER': 'tcp/127.0.0.1:7447',
            'ROS_SECURITY_ENCLAVE_OVERRIDE': '/sec/listener',
        }
    )
    result = run_cli(['topic', 'list'], env)
    assert result.returncode == 1
    assert result.stderr.strip() == (
        'SECURITY ERROR: ROS_SECURITY_STRATEGY=Enforce refuses the unencrypted endpoint '
        'tcp/127.0.0.1:7447; use a tls/ endpoint (e.g. tls/127.0.0.1:7447)'
    )


def test_permissive_without_material_runs_unsecured(
    secured: dict[str, str], ros_router: str, procs: list[Any]
) -> None:
    """Permissive: no enclave → a plain node on the plain router, with one warning."""
    env = environ(
        {
            **secured,
            'ROS_SECURITY_STRATEGY': 'Permissive',
            'ROS2LITE_ROUTER': ros_router,
            'ROS_DOMAIN_ID': os.environ['ROS_DOMAIN_ID'],
        }
    )
    talker = start_node(procs, env, 'talker', '/sec/nobody')
    talker.wait_for('Publishing: "Hello World: 1"')
    warnings = [line for line in talker.text().splitlines() if 'SECURITY' in line]
    assert len(warnings) == 1, talker.text()
    assert 'running unsecured' in warnings[0]


def test_permissions_of_another_domain_refused(secured: dict[str, str]) -> None:
    """F2: permissions made for another ROS_DOMAIN_ID: the node and the verb each refuse in
    the same one line under Enforce (before, both ran and heard nothing)."""
    other = str((int(secured['ROS_DOMAIN_ID']) + 1 - 100) % 100 + 100)
    env = environ({**secured, 'ROS_DOMAIN_ID': other})
    reason = (
        f"permissions of enclave /sec/talker cover domain {secured['ROS_DOMAIN_ID']}, not {other}"
    )
    node = run_cli(
        ['run', 'demo_nodes_py', 'talker', '--ros-args', '--enclave', '/sec/talker'], env
    )
    assert node.returncode != 0
    assert node.stderr.splitlines()[0] == (
        f'SECURITY ERROR: {reason} (ROS_SECURITY_STRATEGY=Enforce)'
    ), node.stderr
    verb = run_cli(
        ['topic', 'echo', '--once', '/chatter', 'std_msgs/msg/String'],
        {**env, 'ROS_SECURITY_ENCLAVE_OVERRIDE': '/sec/talker'},
        timeout=20,
    )
    assert verb.returncode == 1
    assert verb.stderr.strip() == f'SECURITY ERROR: {reason} (ROS_SECURITY_STRATEGY=Enforce)'


def test_expired_certificate_refused_alike(secured: dict[str, str]) -> None:
    """An expired enclave certificate: node and verb refuse with the same one line, before
    the router would (which said only 'refused the TLS handshake')."""
    from ros2lite.security.keystore import create_enclave
    from tests.security.test_environment import replace_certificate

    keystore = Path(secured['ROS_SECURITY_KEYSTORE'])
    create_enclave(keystore, '/sec/expired', secured)
    replace_certificate(keystore, '/sec/expired', '/sec/expired', expired=True)
    env = environ(secured)
    node = run_cli(
        ['run', 'demo_nodes_py', 'talker', '--ros-args', '--enclave', '/sec/expired'], env
    )
    verb = run_cli(
        ['topic', 'pub', '--times', '1', '/chatter', 'std_msgs/msg/String'],
        {**env, 'ROS_SECURITY_ENCLAVE_OVERRIDE': '/sec/expired'},
    )
    assert node.returncode != 0 and verb.returncode == 1
    line = verb.stderr.strip()
    assert line.startswith('SECURITY ERROR: the certificate of enclave /sec/expired expired on')
    assert node.stderr.splitlines()[0] == line, node.stderr


def test_graph_tokens_bound_to_the_enclave(secured: dict[str, str]) -> None:
    """R-S10: an enclave declares graph tokens only under its own name and for what its
    permissions allow; a publisher token on a topic it may not publish, or a node token
    naming another enclave, never reaches the graph (it did: /spoofed showed in node list)."""
    import zenoh

    from ros2lite.daemon.security import session_security
    from ros2lite.transport.config import session_config

    env = {**secured, 'ROS_SECURITY_ENCLAVE_OVERRIDE': '/sec/restricted'}
    domain = secured['ROS_DOMAIN_ID']
    string = (
        'std_msgs::msg::dds_::String_/RIHS01_'
        + 'df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18'
    )
    zid = os.urandom(16).hex()
    head = f'@ros2_lv/{domain}/{zid}'
    tokens = [
        f'{head}/1/2/MP/%sec%restricted/%/spoofed_pub/%chatter/{string}/::,10:,:,:,,',
        f'{head}/3/3/NN/%sec%talker/%/spoofed_node',
        f'{head}/4/4/NN/%/%/spoofed_root',
        f'{head}/5/6/MP/%sec%restricted/%/allowed_node/%other/{string}/::,10:,:,:,,',
    ]
    process_env = environ(env)
    session = zenoh.open(session_config(env=process_env, security=session_security(process_env)))
    try:
        declared = [session.liveliness().declare_token(key) for key in tokens]
        listing = ''
        deadline = time.monotonic() + 15
        while '/allowed_node' not in listing and time.monotonic() < deadline:
            verb = run_cli(
                ['node', 'list'],
                environ({**secured, 'ROS_SECURITY_ENCLAVE_OVERRIDE': '/sec/listener'}),
            )
            listing = verb.stdout
        assert '/allowed_node' in listing, listing
        assert 'spoofed' not in listing, listing
        for token in declared:
            token.undeclare()
    finally:
        session.close()


def test_secured_echo_says_when_the_router_goes_and_comes_back(secured: dict[str, str]) -> None:
    """R-F2, secured: a TLS client's echo says when its router goes and when it is back."""
    import zenoh

    from ros2lite.daemon.router import router_security
    from ros2lite.transport.config import router_config

    endpoint = f'tls/127.0.0.1:{free_port()}'
    env = {**secured, 'ROS2LITE_ROUTER': endpoint}
    router = zenoh.open(router_config(env=env, security=router_security(env)))
    echo_proc, echo = start_cli(
        ['topic', 'echo', '/outage', 'std_msgs/msg/String'],
        environ({**env, 'ROS_SECURITY_ENCLAVE_OVERRIDE': '/sec/listener'}),
    )
    pub_proc, _ = start_cli(
        ['topic', 'pub', '-r', '5', '/outage', 'std_msgs/msg/String', '{data: tick}'],
        environ({**env, 'ROS_SECURITY_ENCLAVE_OVERRIDE': '/sec/talker'}),
    )
    try:
        echo.wait_for('data: tick')  # connected, authenticated, hearing
        router.close()
        echo.wait_for(f'Lost the link to the Zenoh router at {endpoint}', timeout=10)
        router = zenoh.open(router_config(env=env, security=router_security(env)))
        echo.wait_for(f'The link to the Zenoh router at {endpoint} is back', timeout=15)
    finally:
        for proc in (echo_proc, pub_proc):
            proc.terminate()
            proc.wait(timeout=10)
        router.close()
