"""Shared measuring helpers for the benchmark modules (`bench_*.py`)."""

from __future__ import annotations

import contextlib
import os
import socket
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from typing import Any


def rate(fn: Callable[[], Any], min_time: float = 0.3, repeats: int = 5) -> float:
    """Best-of-`repeats` calls per second, each repeat running at least `min_time`."""
    n = 1
    while True:
        t0 = time.perf_counter()
        for _ in range(n):
            fn()
        dt = time.perf_counter() - t0
        if dt >= min_time / 4:
            break
        n *= 2
    best = 0.0
    for _ in range(repeats):
        t0 = time.perf_counter()
        for _ in range(n):
            fn()
        best = max(best, n / (time.perf_counter() - t0))
    return best


def report(name: str, value: float, unit: str, ratio: float) -> None:
    print(f'{name} {value:.6g} {unit} {ratio:.3f}', flush=True)


def wall(cmd: list[str], runs: int = 15) -> float:
    """Median wall time of a whole process, in seconds."""
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
        times.append(time.perf_counter() - t0)
    times.sort()
    return times[len(times) // 2]


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(('127.0.0.1', 0))
        return int(sock.getsockname()[1])


def cli_env(endpoint: str, domain: str, runtime: str) -> dict[str, str]:
    """The environment of a measured CLI process: our router and domain, and byte-code
    caching as an installed package has it (pip compiles on install): a private pycache
    prefix, so a PYTHONDONTWRITEBYTECODE shell can't make every run recompile the sources
    (the baseline gets the same treatment)."""
    env = {
        **os.environ,
        'ROS2LITE_ROUTER': endpoint,
        'ROS_DOMAIN_ID': domain,
        'XDG_RUNTIME_DIR': runtime,
        'PYTHONPYCACHEPREFIX': os.path.join(runtime, 'pyc'),
    }
    for var in (
        'ZENOH_CONFIG_OVERRIDE',
        'ZENOH_SESSION_CONFIG_URI',
        'ZENOH_ROUTER_CONFIG_URI',
        'PYTHONDONTWRITEBYTECODE',
    ):
        env.pop(var, None)
    return env


@contextlib.contextmanager
def environment(env: dict[str, str]) -> Iterator[None]:
    """Run the block with exactly `env` as this process' environment."""
    saved = dict(os.environ)
    os.environ.clear()
    os.environ.update(env)
    try:
        yield
    finally:
        os.environ.clear()
        os.environ.update(saved)


def import_click_wall(runs: int = 9) -> float:
    """The CLI baseline: `python -c 'import click'` (cache warmed first)."""
    import sys

    wall([sys.executable, '-c', 'import click'], runs=1)
    return wall([sys.executable, '-c', 'import click'], runs=runs)


# a router on argv[1] until its stdin closes; with `--env` it reads the environment's
# configuration (security, config files), else only its built-in defaults
ROUTER = r'''
import sys, zenoh
from ros2lite.daemon.router import router_security
from ros2lite.transport.config import router_config
zenoh.init_log_from_env_or('error')
env = None if '--env' in sys.argv else {}
router = zenoh.open(router_config(sys.argv[1], env=env, security=router_security(env)))
print('ready', flush=True)
sys.stdin.read()
router.close()
'''


@contextlib.contextmanager
def ready_child(
    code: str, *args: str, env: dict[str, str] | None = None, timeout: float = 10.0
) -> Iterator[subprocess.Popen[str]]:
    """`python -c code args` with piped stdin/stdout, once it has printed `ready`. Closing its
    stdin on leaving is its cue to finish; it gets `timeout` s before it is killed."""
    proc = subprocess.Popen(
        [sys.executable, '-c', code, *args],
        stdin=subprocess.PIPE,
        stdout=subprocess.PIPE,
        text=True,
        env=env,
    )
    assert proc.stdin is not None and proc.stdout is not None
    try:
        if proc.stdout.readline().strip() != 'ready':
            raise RuntimeError(f'benchmark child {args} did not start')
        yield proc
    finally:
        proc.stdin.close()
        try:
            proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()


def router_process(
    endpoint: str, env: dict[str, str] | None = None, *, configured: bool = False
) -> contextlib.AbstractContextManager[subprocess.Popen[str]]:
    """A router process on `endpoint` (a process of its own: in the measuring process it
    would share zenoh's runtime threads with what is measured); `configured` lets it read
    the environment's configuration."""
    return ready_child(ROUTER, endpoint, *(['--env'] if configured else []), env=env)


class Terminal:
    """A process on a pseudo-terminal of `rows` x `cols`, its output read on a thread into
    `chunks` (a terminal program draws only when it sees a terminal)."""

    def __init__(self, cmd: list[str], env: dict[str, str], rows: int, cols: int) -> None:
        import fcntl
        import pty
        import struct
        import termios
        import threading

        self._master, slave = pty.openpty()
        fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack('HHHH', rows, cols, 0, 0))
        self.proc = subprocess.Popen(cmd, env=env, stdin=slave, stdout=slave, stderr=slave)
        os.close(slave)
        self.chunks: list[bytes] = []
        self._stop = threading.Event()
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self) -> None:
        import select

        while not self._stop.is_set():
            ready, _, _ = select.select([self._master], [], [], 0.1)
            if ready:
                try:
                    self.chunks.append(os.read(self._master, 65536))
                except OSError:
                    return

    def output(self) -> bytes:
        return b''.join(self.chunks)

    def close(self) -> None:
        """Ctrl-C to the process, as a person ends it; then the reader and the terminal."""
        self._stop.set()
        self.proc.send_signal(2)
        self.proc.wait(10)
        self._reader.join(2)
        os.close(self._master)
