"""`multicast receive` as a process, `multicast send` through the CLI, on loopback."""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from typing import Any

import pytest

from tests.cli.conftest import Result
from tests.spinning import free_port
from tests.tools.test_multicast import multicast_on_loopback

Run = Callable[..., Result]


def test_send_receive(run: Run, processes: Any) -> None:
    port = free_port()
    if not multicast_on_loopback(port):
        pytest.skip('this machine has no multicast route on loopback')
    where = ('--port', str(port), '--interface', '127.0.0.1')
    receiver = processes.cli('multicast', 'receive', *where, '-t', '30')
    deadline = time.monotonic() + 30
    while receiver.poll() is None and time.monotonic() < deadline:
        sent = run('multicast', 'send', *where, '--ttl', '0')
        assert (sent.code, sent.out) == (0, 'Sending one UDP multicast datagram...\n')
        time.sleep(0.1)  # until the receiver has joined and heard one
    out, err = processes.stop(receiver)
    assert receiver.returncode == 0, err
    lines = out.splitlines()
    assert lines[0] == 'Waiting for UDP multicast datagram...'
    assert lines[1].startswith('Received from 127.0.0.1:') and lines[1].endswith(": 'Hello World!'")
    assert len(lines) == 2
    assert 'multicast scouting' in err


def test_receive_json(run: Run, processes: Any) -> None:
    port = free_port()
    if not multicast_on_loopback(port):
        pytest.skip('this machine has no multicast route on loopback')
    where = ('--port', str(port), '--interface', '127.0.0.1')
    receiver = processes.cli('multicast', 'receive', *where, '-t', '30', '--json')
    deadline = time.monotonic() + 30
    while receiver.poll() is None and time.monotonic() < deadline:
        run('multicast', 'send', *where, '--ttl', '0')
        time.sleep(0.1)  # until the receiver has joined and heard one
    out, err = processes.stop(receiver)
    assert receiver.returncode == 0, err
    got = json.loads(out)  # stdout holds the one document; the waiting line is on stderr
    assert got['sender'] == '127.0.0.1' and isinstance(got['sender_port'], int)
    assert (got['group'], got['port'], got['data']) == ('225.0.0.1', port, 'Hello World!')
    assert 'Waiting for UDP multicast datagram...' in err


def test_receive_timeout_and_bad_input(run: Run) -> None:
    timed_out = run(
        'multicast', 'receive', '--port', str(free_port()), '--interface', '127.0.0.1', '-t', '0.2'
    )
    assert timed_out.code == 1 and timed_out.out == 'Waiting for UDP multicast datagram...\n'
    assert timed_out.err.startswith('No UDP multicast datagram to 225.0.0.1:')
    assert len(timed_out.err.splitlines()) == 1
    bad = run('multicast', 'send', '--group', '10.1.2.3')
    assert (bad.code, bad.out) == (1, '')  # checked before anything is said or sent
    assert bad.err == "'10.1.2.3' is not a multicast address (224.0.0.0/4)\n"
    assert run('multicast', 'send', '--ttl', '300').code == 2  # a usage error
