"""Lifecycle and component benchmarks: whole CLI processes against live nodes.

`lifecycle_set`: `ros2lite lifecycle set /lc_talker configure|cleanup` (alternating, so every
run is a real transition): start-up, connecting, finding the managed node, asking for its
transitions, the change_state call, printing. Target: under 300 ms.
`component_load`: `ros2lite component load /ComponentManager composition composition::Talker`
into a running container (each loaded talker is unloaded again, untimed). Target: under
300 ms. Baseline for both: `python -c 'import click'` in the same environment.
"""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator

from common import cli_env, environment, free_port, import_click_wall, report, router_process


@contextlib.contextmanager
def graph_with(node_module: str) -> Iterator[tuple[dict[str, str], str]]:
    """A router on a free port and the node `python -m node_module` against it."""
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    with tempfile.TemporaryDirectory() as runtime:
        env = cli_env(endpoint, '218', runtime)
        node = None
        with router_process(endpoint, env):
            try:
                node = subprocess.Popen(
                    [sys.executable, '-m', node_module],
                    env=env,
                    stdout=subprocess.DEVNULL,
                    stderr=subprocess.DEVNULL,
                )
                yield env, os.path.join(os.path.dirname(sys.executable), 'ros2lite')
            finally:
                if node is not None:
                    node.terminate()
                    node.wait(timeout=10)


def _until(cmd: list[str], env: dict[str, str], expected: str) -> None:
    """Run `cmd` until it prints `expected` (the node is up), or fail after 20 s."""
    deadline = time.monotonic() + 20
    while True:
        out = subprocess.run(cmd, env=env, capture_output=True, text=True).stdout
        if out == expected:
            return
        assert time.monotonic() < deadline, out
        time.sleep(0.1)


def _timed(cmd: list[str], env: dict[str, str]) -> tuple[float, str]:
    t0 = time.perf_counter()
    out = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True).stdout
    return time.perf_counter() - t0, out


def _median(times: list[float]) -> float:
    return sorted(times)[len(times) // 2]


def bench_lifecycle_set() -> None:
    with graph_with('ros2lite.bundled.lifecycle_py.lifecycle_talker') as (env, exe):
        _until([exe, 'lifecycle', 'get', '/lc_talker'], env, 'unconfigured [1]\n')
        times = []
        for i in range(15):
            transition = 'configure' if i % 2 == 0 else 'cleanup'
            dt, out = _timed([exe, 'lifecycle', 'set', '/lc_talker', transition], env)
            assert out == 'Transitioning successful\n', out
            times.append(dt)
        with environment(env):
            base = import_click_wall()
    ours = _median(times)
    report('lifecycle_set_wall', ours * 1000, 'ms', ours / base)


def bench_component_load() -> None:
    module = 'ros2lite.bundled.rclpy_components.component_container'
    with graph_with(module) as (env, exe):
        _until([exe, 'component', 'list', '--containers-only'], env, '/ComponentManager\n')
        times = []
        for _ in range(15):
            load = [exe, 'component', 'load', '-q', '/ComponentManager', 'composition']
            dt, out = _timed([*load, 'composition::Talker'], env)
            times.append(dt)
            subprocess.run(
                [exe, 'component', 'unload', '/ComponentManager', out.strip()],
                env=env,
                capture_output=True,
                check=True,
            )
        with environment(env):
            base = import_click_wall()
    ours = _median(times)
    report('component_load_wall', ours * 1000, 'ms', ours / base)


BENCHES = {'lifecycle_set': bench_lifecycle_set, 'component_load': bench_component_load}
