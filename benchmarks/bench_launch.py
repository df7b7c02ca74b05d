"""`ros2lite launch` of a two-node file: time until the nodes talk, and Ctrl-C trials.

Arrangement: a router process on a free loopback port and a private domain; each run starts
the whole `ros2lite launch demo_nodes_py talker_listener.launch.py` process and measures the
wall time until the listener prints its first `I heard` (the talker publishes once a second,
starting one period after it is up, as ROS's demo does). The baseline is the same two nodes
started by hand, `ros2lite run demo_nodes_py talker` and `… listener` at once, measured the
same way: the ratio is what launch adds.

Reported:
* `launch_two_nodes_talking <ms> ms <ratio vs two ros2lite run>` — median of 5 runs each;
* `launch_ctrl_c_clean <n> of-20-trials <fraction>` — Ctrl-C (SIGINT to the terminal's
  foreground group, the launch run in a pseudo-terminal) at moments from start-up to
  talking; a trial is clean when the launch exits 0 and no process it started (found by a
  marker in their environment, whatever their session) is left running;
* `launch_ctrl_c_stop <ms> ms 1` — the median time from Ctrl-C to the launch's exit.
"""

from __future__ import annotations

import os
import pty
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import uuid
from collections.abc import Iterator
from contextlib import contextmanager

from common import cli_env, free_port, report, router_process

RUNS = 5
TRIALS = 20


@contextmanager
def _router() -> Iterator[dict[str, str]]:
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    with tempfile.TemporaryDirectory() as runtime:
        env = cli_env(endpoint, '219', runtime)
        env['ROS2LITE_NO_DAEMON'] = '1'
        with router_process(endpoint, env):
            yield env


def _until_heard(cmds: list[list[str]], env: dict[str, str], timeout: float = 30) -> float:
    """Start the commands at once; seconds until one of them prints `I heard`."""
    heard = threading.Event()
    t0 = time.perf_counter()
    procs = [
        subprocess.Popen(
            cmd,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            env=env,
            start_new_session=True,
        )
        for cmd in cmds
    ]

    def watch(proc: subprocess.Popen[str]) -> None:
        assert proc.stdout is not None
        for line in proc.stdout:
            if 'I heard' in line:
                heard.set()

    for proc in procs:
        threading.Thread(target=watch, args=(proc,), daemon=True).start()
    try:
        if not heard.wait(timeout):
            raise RuntimeError('the nodes did not talk')
        return time.perf_counter() - t0
    finally:
        for proc in procs:
            proc.send_signal(signal.SIGINT)
        for proc in procs:
            try:
                proc.wait(15)
            except subprocess.TimeoutExpired:
                proc.kill()


def _marked(marker: str) -> list[int]:
    found = []
    for entry in os.listdir('/proc'):
        if entry.isdigit():
            try:
                with open(f'/proc/{entry}/environ', 'rb') as f:
                    if marker.encode() in f.read():
                        found.append(int(entry))
            except OSError:
                pass
    return found


def _ctrl_c_trial(cmd: list[str], env: dict[str, str], delay: float | None) -> tuple[bool, float]:
    """One trial; (clean, seconds from Ctrl-C to exit)."""
    import fcntl
    import termios

    marker = uuid.uuid4().hex
    master, slave = pty.openpty()

    def take_terminal() -> None:
        fcntl.ioctl(0, termios.TIOCSCTTY, 0)

    talking = threading.Event()
    started = threading.Event()
    proc = subprocess.Popen(
        cmd,
        stdin=slave,
        stdout=subprocess.PIPE,
        stderr=subprocess.STDOUT,
        text=True,
        env={**env, 'ROS2LITE_TRIAL': marker},
        start_new_session=True,
        preexec_fn=take_terminal,
    )
    lines: list[str] = []

    def watch() -> None:
        assert proc.stdout is not None
        for line in proc.stdout:
            lines.append(line)
            if 'process started' in line:
                started.set()
            if 'I heard' in line:
                talking.set()

    threading.Thread(target=watch, daemon=True).start()
    try:
        if delay is None:
            talking.wait(30)
        else:
            time.sleep(delay)
        t0 = time.perf_counter()
        os.killpg(proc.pid, signal.SIGINT)
        code = proc.wait(60)
        stop = time.perf_counter() - t0
    finally:
        if proc.poll() is None:
            proc.kill()
        os.close(master)
        os.close(slave)
    deadline = time.monotonic() + 5
    while _marked(marker) and time.monotonic() < deadline:
        time.sleep(0.05)
    left = _marked(marker)
    ran = started.is_set()
    clean = not left and (code == 0 or not ran) and not any('escalating' in x for x in lines)
    if not clean:
        print(f'# unclean trial: exit {code}, left {left}', file=sys.stderr)
    return clean, stop


def bench_launch() -> None:
    launch = [
        sys.executable,
        '-m',
        'ros2lite',
        'launch',
        'demo_nodes_py',
        'talker_listener.launch.py',
    ]
    by_hand = [
        [sys.executable, '-m', 'ros2lite', 'run', 'demo_nodes_py', 'talker'],
        [sys.executable, '-m', 'ros2lite', 'run', 'demo_nodes_py', 'listener'],
    ]
    with _router() as env:
        _until_heard([launch], env)  # warm the byte-code cache
        ours, base = [], []
        for _ in range(RUNS):
            ours.append(_until_heard([launch], env))
            base.append(_until_heard(by_hand, env))
        if os.environ.get('BENCH_LAUNCH_VERBOSE'):
            load = ', '.join(f'{x:.2f}' for x in os.getloadavg())
            print('# launch', [round(t, 3) for t in ours], 'by hand', [round(t, 3) for t in base])
            print(f'# load average during the runs: {load} on {os.cpu_count()} cores')
        report(
            'launch_two_nodes_talking',
            statistics.median(ours) * 1000,
            'ms',
            statistics.median(ours) / statistics.median(base),
        )
        delays: list[float | None] = [0.02, 0.1, 0.3, 0.6, 0.9] + [None] * (TRIALS - 5)
        results = [_ctrl_c_trial(launch, env, d) for d in delays]
        clean = sum(ok for ok, _ in results)
        report('launch_ctrl_c_clean', clean, f'of-{TRIALS}-trials', clean / TRIALS)
        stops = [s for ok, s in results]
        report('launch_ctrl_c_stop', statistics.median(stops) * 1000, 'ms', 1.0)


BENCHES = {'launch': bench_launch}
