"""Two meshed daemons across a lossy link that is cut for 5 s (network namespaces, a veth
pair, tc/nftables): reliable delivery loses nothing, the flow is back at once when the link
is, the recorded bag is whole, and services answer across the link afterwards.

The scenario lives in benchmarks/bench_link.py, which prints the same numbers."""

from __future__ import annotations

import sys
from pathlib import Path

import pytest

BENCHMARKS = Path(__file__).resolve().parents[2] / 'benchmarks'


def test_reliable_across_a_lossy_cut_link(tmp_path: Path) -> None:
    sys.path.insert(0, str(BENCHMARKS))
    try:
        from bench_link import COUNT, Unavailable, cross
    finally:
        sys.path.remove(str(BENCHMARKS))
    try:
        outcome = cross(tmp_path)
    except Unavailable as exc:
        pytest.skip(f'no network namespaces here: {exc}')
    assert outcome.published == COUNT
    for who in ('reliable', 'echo'):
        assert outcome.missing(who) == 0, (who, outcome.impairment)
    assert outcome.bag == COUNT
    assert 0 <= outcome.recovery < 2.0, outcome.recovery
    assert outcome.hz_after_cut
    assert outcome.param_get == 'Boolean value is: False', outcome.param_get
    assert outcome.service_call


def test_the_daemon_says_when_its_mesh_link_goes_and_comes_back(tmp_path: Path) -> None:
    """A router meshed with ours goes away: our daemon's log says so (tools on our side
    would not notice, their own router being fine), and says so again when it is back."""
    import os
    import subprocess

    import zenoh

    from ros2lite.transport.config import router_config
    from tests.spinning import free_port
    from tests.transport.test_security import Lines

    far, near = f'tcp/127.0.0.1:{free_port()}', f'tcp/127.0.0.1:{free_port()}'
    router = zenoh.open(router_config(far, env={}))
    zid = str(router.zid())
    runtime = tmp_path / 'run'
    runtime.mkdir(mode=0o700)
    env = {k: v for k, v in os.environ.items() if not k.startswith('ZENOH_')}
    env['XDG_RUNTIME_DIR'] = str(runtime)
    daemon = [sys.executable, '-m', 'ros2lite.daemon', '--foreground']
    proc = subprocess.Popen(
        [*daemon, '--router', near, '--connect', far],
        env=env,
        text=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    try:
        log = Lines(proc)
        log.wait_for(f'ros2lite daemon: linked to router {zid}')
        router.close()
        log.wait_for(f'ros2lite daemon: lost the link to router {zid}: what is published on')
        router = zenoh.open(router_config(far, env={}))
        log.wait_for(f'ros2lite daemon: linked to router {router.zid()}')
    finally:
        proc.terminate()
        proc.wait(timeout=10)
        router.close()
    assert 'lost the link' not in log.text().split('SIGTERM')[-1]  # none said at shutdown
