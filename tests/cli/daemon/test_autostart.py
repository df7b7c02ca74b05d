"""Graph verbs start the daemon when no router answers, unless --no-daemon: then they fail
fast with one line."""

from __future__ import annotations

import time

import pytest

from ros2lite import daemon

from ..conftest import run_process
from .conftest import Private

# each failure costs the ~1 s connect timeout, so a sample: the silent-on-unknown verb must
# still say why it failed here
GRAPH_VERBS = [['topic', 'list'], ['topic', 'type', '/x'], ['node', 'info', '/x']]


@pytest.mark.parametrize('verb', GRAPH_VERBS, ids=lambda v: '_'.join(v))
def test_no_daemon_without_router_fails_fast(private: Private, verb: list[str]) -> None:
    t0 = time.monotonic()
    result = run_process('--router', private.endpoint, *verb, '--no-daemon', env=private.env)
    elapsed = time.monotonic() - t0
    assert result.code == 1 and result.out == ''
    assert result.err.startswith(f'No Zenoh router answers at {private.endpoint}')
    assert result.err.count('\n') == 1
    assert elapsed < 3.0, elapsed
    assert not daemon.status(private.endpoint).running  # nothing was started


def test_graph_verb_starts_the_daemon(private: Private) -> None:
    assert not daemon.status(private.endpoint).running
    result = run_process('--router', private.endpoint, 'topic', 'list', env=private.env)
    assert (result.code, result.out) == (0, '')
    st = daemon.status(private.endpoint)
    # not the default endpoint: a typo there would make an empty graph, so it is said once
    assert result.err.count('\n') == 1
    assert (
        f'no Zenoh router answered at {private.endpoint}: started the ros2lite daemon there '
        f'(pid {st.pid}), a graph of its own at the endpoint --router or ROS2LITE_ROUTER named'
    ) in result.err
    assert st.running and st.ours
    # the next call just uses it
    again = run_process('node', 'list', env=private.env)
    assert (again.code, again.out, again.err) == (0, '', '')
    assert daemon.status(private.endpoint).pid == st.pid
    stop = run_process('daemon', 'stop', env=private.env)
    assert stop.out == 'The daemon has been stopped\n'
