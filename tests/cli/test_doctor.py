"""`doctor` / `wtf` against live graphs made of hand-declared rmw_zenoh tokens: a healthy
one, lonely endpoints, mismatched type hashes, incompatible QoS, and no router at all."""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from ros2lite.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from tests.cli.conftest import Result
from tests.cli.graph_helpers import STRING_HASH, TokenGraph, fake_hash, private_domain
from tests.spinning import free_port, wait_until


@pytest.fixture
def graph(ros_router: str, monkeypatch: pytest.MonkeyPatch) -> Iterator[TokenGraph]:
    # the interpreter running the tests is the `python3` a user would type
    monkeypatch.setenv('PATH', os.path.dirname(sys.executable) + os.pathsep + os.environ['PATH'])
    domain = private_domain(monkeypatch)
    with TokenGraph(domain) as g:
        yield g


def _findings(err: str) -> list[str]:
    """The messages of the warning lines (after '<file>: <line>: UserWarning: ')."""
    out = []
    for line in err.splitlines():
        where, sep, message = line.partition(': UserWarning: ')
        filename, _, lineno = where.rpartition(': ')
        assert sep and filename.endswith('doctor.py') and lineno.isdigit(), line
        out.append(message)
    return out


def test_healthy(run: Callable[..., Result], graph: TokenGraph) -> None:
    graph.node('talker').pub('/chatter', type_hash=STRING_HASH)
    graph.node('listener').sub('/chatter', type_hash=STRING_HASH)
    for verb in ('doctor', 'wtf'):
        result = run(verb)
        assert (result.code, result.out, result.err) == (0, '\nAll 6 checks passed\n\n', '')


def test_lonely_endpoints_are_warnings(run: Callable[..., Result], graph: TokenGraph) -> None:
    node = graph.node('talker')
    node.pub('/lonely')
    node.sub('/nobody_talks')
    result = run('doctor')
    assert result.out == '\nAll 6 checks passed\n\n'
    assert _findings(result.err) == [
        'Publisher without subscriber detected on /lonely.',
        'Subscriber without publisher detected on /nobody_talks.',
    ]
    strict = run('doctor', '--include-warnings')
    assert strict.out == '\n1/6 check(s) failed\n\nFailed modules: topic\n'


def test_type_hash_mismatch_is_an_error(run: Callable[..., Result], graph: TokenGraph) -> None:
    graph.node('talker').pub('/chatter', type_hash=fake_hash('old String'))
    graph.node('listener').sub('/chatter', type_hash=STRING_HASH)
    result = run('doctor', '-rf')
    assert result.out.startswith('\n1/6 check(s) failed\n\nFailed modules: topic\n')
    old, new = sorted([(fake_hash('old String'), '/talker'), (STRING_HASH, '/listener')])
    assert _findings(result.err) == [
        f'ERROR: Type hash mismatch on /chatter (std_msgs/msg/String): {old[0]} ({old[1]}), '
        f'{new[0]} ({new[1]}); these endpoints never exchange a message'
    ]
    # the failed module's report follows, in ros2doctor's layout
    assert result.out.endswith(
        '\n   TOPIC LIST\n'
        'topic               : /chatter\n'
        'publisher count     : 1\n'
        'subscriber count    : 1\n'
    )


def test_qos_by_rmw_zenohs_rule(run: Callable[..., Result], graph: TokenGraph) -> None:
    """A pair DDS calls incompatible (best effort to reliable) is fine on rmw_zenoh, whose
    check never answers incompatible; its one warning (transient local to volatile) shows
    in the report and fails nothing."""
    best_effort = QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT)
    graph.node('camera').pub('/image', qos=best_effort)
    graph.node('viewer').sub('/image', qos=QoSProfile(depth=10))
    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    graph.node('mapper').pub('/map', qos=latched)
    graph.node('planner').sub('/map', qos=QoSProfile(depth=1))
    checked = run('doctor', '-iw')
    assert checked.code == 0 and 'All 6 checks passed' in checked.out, checked
    result = run('doctor', '-r')
    assert '\n   QOS COMPATIBILITY LIST\n' in result.out
    assert 'publisher node          : /camera\n' in result.out
    assert (
        "compatibility status    : WARNING: Publisher's durability is TRANSIENT_LOCAL, but "
        "subscription's is VOLATILE;\n" in result.out
    )


def test_no_router(run: Callable[..., Result], monkeypatch: pytest.MonkeyPatch) -> None:
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    monkeypatch.setenv('ROS2LITE_ROUTER', endpoint)
    monkeypatch.setenv('PATH', os.path.dirname(sys.executable) + os.pathsep + os.environ['PATH'])
    result = run('doctor')
    assert result.out == '\n1/6 check(s) failed\n\nFailed modules: network\n'
    assert _findings(result.err) == [
        f'ERROR: No Zenoh router answers at {endpoint}: start one with `ros2lite daemon start` '
        '(or rmw_zenohd)',
        'topics not checked: no Zenoh router answers',
        'QoS not checked: no Zenoh router answers',
    ]


def test_bad_environment(run: Callable[..., Result], graph: Any, monkeypatch: Any) -> None:
    monkeypatch.setenv('ROS_DOMAIN_ID', 'abc')
    monkeypatch.setenv('RMW_IMPLEMENTATION', 'rmw_fastrtps_cpp')
    result = run('doctor')
    assert 'Failed modules: middleware' in result.out
    findings = _findings(result.err)
    assert "ERROR: ROS_DOMAIN_ID is not an integral number: 'abc'" in findings, findings
    assert any(f.startswith('RMW_IMPLEMENTATION is rmw_fastrtps_cpp') for f in findings)


def test_domain_ids_rcl_reads_otherwise_are_said(
    run: Callable[..., Result], graph: Any, monkeypatch: Any
) -> None:
    """rmw_zenoh joins domains above DDS's 232, and rcl reads `010` as octal: both are
    warnings (the node runs), not errors."""
    for raw, said in (
        (
            '999',
            "ROS_DOMAIN_ID '999' is domain 999: rmw_zenoh nodes join it, but DDS-based "
            'ROS 2 nodes only reach domains 0..232',
        ),
        (
            '010',
            "ROS_DOMAIN_ID '010' reads as domain 8 (as rcl reads it: a leading 0 is "
            'octal, 0x hex, and what follows the number is ignored)',
        ),
    ):
        monkeypatch.setenv('ROS_DOMAIN_ID', raw)
        result = run('doctor')
        assert said in ' '.join(result.err.split()), result.err


def test_report_layout(run: Callable[..., Result], graph: TokenGraph) -> None:
    result = run('doctor', '--report')
    assert result.code == 0 and result.err == ''
    sections = [line.strip() for line in result.out.splitlines() if line.startswith('   ')]
    assert sections == [
        'PLATFORM INFORMATION',
        'ROS2LITE INFORMATION',
        'NETWORK CONFIGURATION',
        'RMW MIDDLEWARE',
        'TOPIC LIST',
        'QOS COMPATIBILITY LIST',
        'PACKAGE VERSIONS',
    ]
    assert '\n   TOPIC LIST\ntopic    : none\n' in result.out  # padding: max(8, key + 4)
    assert 'router answers        : yes\n' in result.out
    assert 'PACKAGE VERSIONS' not in run('doctor', '-r', '--exclude-packages').out


def test_type_hash_mismatch_between_real_nodes(
    run: Callable[..., Result],
    ros_router: str,
    processes: Any,
    tmp_path: Any,
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """The broken setup a student makes: `Age.msg` gains a field while a node started from
    the old definition still runs. Same type name, different RIHS01 hashes — doctor names
    both endpoints."""
    from ros2lite.interfaces.hashing import type_hash
    from ros2lite.interfaces.registry import Registry

    monkeypatch.setenv('PATH', os.path.dirname(sys.executable) + os.pathsep + os.environ['PATH'])
    private_domain(monkeypatch)
    definitions = {'old': 'uint8 years\n', 'new': 'uint8 years\nuint8 months\n'}
    hashes = {}
    for version, text in definitions.items():
        msg = tmp_path / version / 'lesson_msgs' / 'msg'
        msg.mkdir(parents=True)
        (msg / 'Age.msg').write_text(text)
        hashes[version] = type_hash('lesson_msgs/msg/Age', Registry([tmp_path / version]))
    assert hashes['old'] != hashes['new']

    def cli(version: str, *args: str) -> Any:
        env = {**os.environ, 'ROS2LITE_INTERFACE_PATH': str(tmp_path / version)}
        cmd = [sys.executable, '-m', 'ros2lite', *args]
        return processes.start(cmd, env=env, stdin=subprocess.DEVNULL)

    cli('old', 'topic', 'pub', '/age', 'lesson_msgs/msg/Age', '{years: 7}')
    cli('new', 'topic', 'echo', '/age', 'lesson_msgs/msg/Age')

    def diagnosed() -> Result | None:
        result = run('doctor')
        return result if 'Type hash mismatch' in result.err else None

    result = wait_until(diagnosed, timeout=30, interval=0.2)
    assert result.code == 0  # doctor reports; it does not fail the shell
    assert result.out == '\n1/6 check(s) failed\n\nFailed modules: topic\n'
    (finding,) = [f for f in _findings(result.err) if 'Type hash mismatch' in f]
    assert finding.startswith('ERROR: Type hash mismatch on /age (lesson_msgs/msg/Age): ')
    assert hashes['old'] in finding and hashes['new'] in finding
    assert finding.endswith('; these endpoints never exchange a message')


def test_old_rmw_zenoh_peers_are_named(run: Callable[..., Result], graph: TokenGraph) -> None:
    """Hand-made tokens as rmw_zenoh 0.2.0-0.2.2 writes them (TRANSIENT_LOCAL was its
    default: volatile written `2`, /rosout's transient-local left empty), beside a current
    node's: only the old nodes are named, with the advice to upgrade."""
    rosout_qos = QoSProfile(depth=1000, durability=DurabilityPolicy.TRANSIENT_LOCAL)

    def old(key: str, chunk: str) -> None:
        graph.undeclare(key)
        graph.declare(key.rsplit('/', 1)[0] + '/' + chunk)

    events = 'rcl_interfaces/msg/ParameterEvent'
    old_talker = graph.node('old_talker', zid='1' * 32)
    old(old_talker.pub('/parameter_events', events), ':2:,1000:,:,:,,')
    old_listener = graph.node('old_listener', '/robot', zid='2' * 32)
    old(old_listener.pub('/rosout', 'rcl_interfaces/msg/Log', rosout_qos), '::,1000:,:10,0:,,')
    current = graph.node('current')
    current.pub('/rosout', 'rcl_interfaces/msg/Log', rosout_qos)
    current.pub('/parameter_events', events)
    current.sub('/parameter_events', events)
    result = run('doctor')
    assert result.code == 0
    advice = [f for f in _findings(result.err) if 'rmw_zenoh 0.2.0-0.2.2' in f]
    assert [f.split(':')[0] for f in advice] == ['node /old_talker', 'node /robot/old_listener']
    assert all('upgrade rmw_zenoh_cpp' in f for f in advice)
