"""One rclpy program on real rclpy (ROS 2 Jazzy, Fast DDS) and on ros2lite, in the same run.

`rclpy_program.py` next to this file uses rclpy's public API only; both stacks run that one
file, so the figures compare the libraries as a user's code meets them:

* real rclpy: Jazzy's wheels from the package registry (`ros-jazzy-rclpy[fastrtps]`,
  `std-msgs`, `sensor-msgs`, `std-srvs`) in a venv at `$VS_RCLPY_VENV` or
  `~/.cache/vs-rclpy-venv`, built on first use (never in CI: benchmarks do not run there).
  Every real-rclpy process is confined to loopback: `fastdds_loopback.xml` (UDP on 127.0.0.1
  and shared memory, no multicast), `ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST`, a private
  domain. Without the venv the benchmark says so in one line and is skipped.
* ros2lite: the environment `ros2lite env` prints (its rclpy face on PYTHONPATH) applied to
  the child, a router process on a free loopback port, a private domain; the python of this
  process, or `$VS_LITE_PYTHON`.

Figures (QoS reliable, keep last 1000): `tp_small` String msg/s (subscriber spun by
`spin_until_future_complete`), `tp_image` MB/s of 1 MiB `sensor_msgs/Image`, `spin_once_loop`
msg/s (the tutorials' `spin_once` loop), `latency_p50/p99` µs (ping-pong through an echo
process, one message in flight), `service_p50/p99` µs (`call_async` +
`spin_until_future_complete`), `service_call_p50` µs (`Client.call()` with an executor
spinning on another thread), `startup_to_delivery` ms (from starting a process until a
subscriber in another process has its first message).

Each figure prints as `vs_rclpy_<figure> <ros2lite> unit <ratio>` with ratio = ros2lite / real
rclpy (higher is better for throughput, lower is better for times), followed by
`vs_rclpy_<figure>_real_rclpy <real> unit 1.0`. Values are medians of VS_RCLPY_ROUNDS (3)
rounds, the stacks interleaved within each round; VS_RCLPY_SECS (3) is the length of a
throughput run; VS_RCLPY_ONLY="tp_small tp_image once latency service startup" picks
scenarios; VS_LITE_SHM=1 turns shared memory on for ros2lite (as rmw_zenoh's config key does).
A round without a RESULT line is reported on stderr and left out.
"""

from __future__ import annotations

import contextlib
import os
import random
import shlex
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from common import report

HERE = Path(__file__).resolve().parent
PROGRAM = HERE / 'rclpy_program.py'
PROFILE = HERE / 'fastdds_loopback.xml'
REAL_PACKAGES = (
    'ros-jazzy-rclpy[fastrtps]',
    'ros-jazzy-std-msgs',
    'ros-jazzy-sensor-msgs',
    'ros-jazzy-std-srvs',
)
REAL_CHECK = 'import rclpy, std_srvs, sensor_msgs'
SCENARIOS = ('tp_small', 'tp_image', 'once', 'latency', 'service', 'startup')
# figure → unit, in the order they print; throughput first, then times
FIGURES = {
    'tp_small': 'msg/s',
    'tp_image': 'MB/s',
    'spin_once_loop': 'msg/s',
    'latency_p50': 'us',
    'latency_p99': 'us',
    'service_p50': 'us',
    'service_p99': 'us',
    'service_call_p50': 'us',
    'startup_to_delivery': 'ms',
}
SMALL, IMAGE = 16, 1 << 20
PINGS, CALLS = 2000, 1000
CHILD_TIMEOUT = 90.0  # no role may run longer than this
READY_TIMEOUT = 20.0
STOP_GRACE = 3.0  # SIGTERM, then SIGKILL after this many seconds
# what could point real rclpy at other configuration or at ros2lite's rclpy face
_FOREIGN = (
    'PYTHONPATH',
    'PYTHONHOME',
    'AMENT_PREFIX_PATH',
    'ROS_LOCALHOST_ONLY',
    'ROS_STATIC_PEERS',
    'RMW_IMPLEMENTATION',
    'FASTDDS_DEFAULT_PROFILES_FILE',
    'FASTRTPS_DEFAULT_PROFILES_FILE',
    'ROS_DISCOVERY_SERVER',
    'ROS_SECURITY_ENABLE',
    'ROS2LITE_ROUTER',
)


class Unavailable(Exception):
    """A stack that cannot run here (no real rclpy, no `ros2lite env`): the run is skipped."""


@dataclass
class Stack:
    """How to start the program on one stack: its interpreter and its whole environment."""

    name: str
    python: str
    env: dict[str, str]
    values: dict[str, list[float]] = field(default_factory=dict)

    def start(self, *args: str, cwd: str) -> subprocess.Popen[str]:
        return subprocess.Popen(
            [self.python, str(PROGRAM), *args],
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            text=True,
            env=self.env,
            cwd=cwd,
        )

    def record(self, figure: str, value: float) -> None:
        self.values.setdefault(figure, []).append(value)


class Child:
    """A started role whose output is read on a thread, so waiting for `ready` is bounded."""

    def __init__(self, stack: Stack, args: tuple[str, ...], cwd: str) -> None:
        self.what = f'{" ".join(args)} on {stack.name}'
        self.proc = stack.start(*args, cwd=cwd)
        self.lines: list[str] = []
        self.is_ready = threading.Event()
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            self.lines.append(line.rstrip('\n'))
            if line.strip() == 'ready':
                self.is_ready.set()

    def wait_ready(self) -> bool:
        return self.is_ready.wait(READY_TIMEOUT)

    def finish(self, timeout: float) -> None:
        """Wait up to `timeout` s for it to leave by itself, then stop it."""
        with contextlib.suppress(subprocess.TimeoutExpired):
            self.proc.wait(timeout)
        self.stop()

    def stop(self) -> None:
        """SIGTERM, then SIGKILL: real rclpy's serving roles do not always leave on SIGTERM."""
        if self.proc.poll() is None:
            self.proc.terminate()
            try:
                self.proc.wait(STOP_GRACE)
            except subprocess.TimeoutExpired:
                self.proc.kill()
                self.proc.wait()
        self.reader.join(STOP_GRACE)

    def result(self) -> dict[str, str] | None:
        """The fields of its RESULT line. Its exit status is not looked at: real rclpy's
        `client_sync` aborts at exit ("terminate called without an active exception")
        after it has printed a complete result."""
        for line in reversed(self.lines):
            if line.startswith('RESULT '):
                return dict(w.split('=', 1) for w in line.split()[2:] if '=' in w)
        return None

    def complain(self) -> None:
        last = next((s for s in reversed(self.lines) if s.strip()), '(no output)')
        print(
            f'vs_rclpy: {self.what}: no result (exit {self.proc.returncode}): {last[-200:]}',
            file=sys.stderr,
        )


def real_rclpy_python() -> str:
    """The interpreter of the real-rclpy venv, built once if missing or incomplete."""
    cache = Path(os.environ.get('XDG_CACHE_HOME') or Path.home() / '.cache')
    venv = Path(os.environ.get('VS_RCLPY_VENV') or cache / 'vs-rclpy-venv')
    python = venv / 'bin' / 'python'
    if python.exists() and _imports_rclpy(str(python)):
        return str(python)
    print(f'vs_rclpy: building real rclpy in {venv} (once)...', file=sys.stderr, flush=True)
    steps = [
        [sys.executable, '-m', 'venv', str(venv)],
        [str(python), '-m', 'pip', 'install', '-q', *REAL_PACKAGES],
    ]
    for step in steps:
        done = subprocess.run(step, capture_output=True, text=True)
        if done.returncode != 0:
            tail = (done.stderr.strip().splitlines() or ['?'])[-1]
            raise Unavailable(f'could not build real rclpy in {venv}: {tail}')
    if not _imports_rclpy(str(python)):
        raise Unavailable(f'real rclpy in {venv} does not import ({REAL_CHECK})')
    return str(python)


def _imports_rclpy(python: str) -> bool:
    env = confined(dict(os.environ), real_domain())
    done = subprocess.run([python, '-c', REAL_CHECK], capture_output=True, env=env)
    return done.returncode == 0


def real_domain() -> int:
    """A domain for real rclpy outside the ranges the shared tools on this kind of machine
    draw from (ros2cli oracle 43, rclpy suite 1-100, vs-rclpy 150-199): real rclpy processes
    on one domain find each other through the loopback peers."""
    return random.randint(200, 232)


def confined(base: dict[str, str], domain: int) -> dict[str, str]:
    """The environment every real-rclpy process gets: loopback-only Fast DDS, localhost
    discovery, a private domain, nothing of ros2lite's."""
    env = {k: v for k, v in base.items() if k not in _FOREIGN}
    env.update(
        FASTRTPS_DEFAULT_PROFILES_FILE=str(PROFILE),
        FASTDDS_DEFAULT_PROFILES_FILE=str(PROFILE),
        ROS_AUTOMATIC_DISCOVERY_RANGE='LOCALHOST',
        ROS_DOMAIN_ID=str(domain),
        RMW_IMPLEMENTATION='rmw_fastrtps_cpp',
    )
    return env


def lite_environment(python: str, base: dict[str, str]) -> dict[str, str]:
    """`base` with what `eval "$(ros2lite env)"` would set, for the given interpreter."""
    done = subprocess.run(
        [python, '-m', 'ros2lite', 'env'], capture_output=True, text=True, env=base
    )
    if done.returncode != 0:
        raise Unavailable(f'`{python} -m ros2lite env` failed: {done.stderr.strip()[-200:]}')
    env = dict(base)
    for line in done.stdout.splitlines():
        words = shlex.split(line.rstrip(';'))
        if len(words) == 2 and words[0] == 'export' and '=' in words[1]:
            name, value = words[1].split('=', 1)
            env[name] = value
    if 'PYTHONPATH' not in env:
        raise Unavailable('`ros2lite env` printed no PYTHONPATH')
    return env


def pair(
    stack: Stack, cwd: str, server: tuple[str, ...], client: tuple[str, ...], *, serving: bool
) -> tuple[dict[str, str] | None, dict[str, str] | None]:
    """Start `server`, then run `client` against it; both RESULTs (None where missing).
    A serving role (echo, server) is stopped once the client is done; a subscriber is
    given time to count the last messages and leave by itself."""
    first = Child(stack, server, cwd)
    try:
        if not first.wait_ready():
            first.stop()
            first.complain()
            return None, None
        second = Child(stack, client, cwd)
        second.finish(CHILD_TIMEOUT)
        first.finish(0.0 if serving else 15.0)
    finally:
        first.stop()
    for child in (first, second):
        if child.result() is None and (child is second or not serving):
            child.complain()
    return first.result(), second.result()


def take(stack: Stack, figure: str, fields: dict[str, str] | None, key: str) -> None:
    if fields is not None and key in fields:
        stack.record(figure, float(fields[key]))


def round_of(stack: Stack, only: list[str], secs: str, cwd: str) -> None:
    """Every chosen scenario once on `stack`."""
    for scenario in only:
        if scenario in ('tp_small', 'tp_image', 'once'):
            size = str(IMAGE if scenario == 'tp_image' else SMALL)
            role = 'sub_once' if scenario == 'once' else 'sub'
            sub, _ = pair(stack, cwd, (role, size, secs), ('pub', size, secs), serving=False)
            if scenario == 'tp_image':
                take(stack, 'tp_image', sub, 'mbps')
            else:
                take(stack, 'spin_once_loop' if scenario == 'once' else 'tp_small', sub, 'rate')
        elif scenario == 'latency':
            _, ping = pair(stack, cwd, ('echo',), ('ping', str(PINGS)), serving=True)
            take(stack, 'latency_p50', ping, 'p50')
            take(stack, 'latency_p99', ping, 'p99')
        elif scenario == 'service':
            _, calls = pair(stack, cwd, ('server',), ('client', str(CALLS)), serving=True)
            take(stack, 'service_p50', calls, 'p50')
            take(stack, 'service_p99', calls, 'p99')
            _, calls = pair(stack, cwd, ('server',), ('client_sync', str(CALLS)), serving=True)
            take(stack, 'service_call_p50', calls, 'p50')
        else:
            startup(stack, cwd)


def startup(stack: Stack, cwd: str) -> None:
    """From starting the publishing process until the waiting subscriber has the message."""
    waiting = Child(stack, ('startup_sub',), cwd)
    try:
        if not waiting.wait_ready():
            waiting.complain()
            return
        started = time.monotonic()
        publisher = Child(stack, ('startup',), cwd)
        publisher.finish(CHILD_TIMEOUT)
        waiting.finish(10.0)
    finally:
        waiting.stop()
    got = waiting.result()
    if got is None or 'at' not in got:
        waiting.complain()
        return
    stack.record('startup_to_delivery', (float(got['at']) - started) * 1e3)


@contextlib.contextmanager
def lite_router() -> Iterator[None]:
    """bench_node's private router (free loopback port, private domain, in os.environ)."""
    from bench_node import private_router

    with private_router():
        yield


def chosen() -> list[str]:
    only = os.environ.get('VS_RCLPY_ONLY', ' '.join(SCENARIOS)).replace(',', ' ').split()
    unknown = [s for s in only if s not in SCENARIOS]
    if unknown:
        raise Unavailable(f'VS_RCLPY_ONLY: unknown {", ".join(unknown)}; pick from {SCENARIOS}')
    return only


def bench_vs_rclpy() -> None:
    """The program on both stacks, interleaved per round; medians and ros2lite / real."""
    rounds = int(os.environ.get('VS_RCLPY_ROUNDS', 3))
    secs = os.environ.get('VS_RCLPY_SECS', '3')
    try:
        only = chosen()
        real_python = real_rclpy_python()
    except Unavailable as err:
        print(f'vs_rclpy: skipped: {err}', file=sys.stderr)
        return
    lite_python = os.environ.get('VS_LITE_PYTHON') or sys.executable
    with lite_router(), tempfile.TemporaryDirectory(prefix='vs-rclpy-') as cwd:
        base = dict(os.environ)  # the router and the lite domain, set by lite_router
        try:
            lite_env = lite_environment(lite_python, base)
        except Unavailable as err:
            print(f'vs_rclpy: skipped: {err}', file=sys.stderr)
            return
        if os.environ.get('VS_LITE_SHM') == '1':  # rmw_zenoh's switch, on the ros2lite side
            lite_env['ZENOH_CONFIG_OVERRIDE'] = 'transport/shared_memory/enabled=true'
        stacks = (
            Stack('real rclpy', real_python, confined(base, real_domain())),
            Stack('ros2lite', lite_python, lite_env),
        )
        for _ in range(rounds):
            for stack in stacks:
                round_of(stack, only, secs, cwd)
    real, lite = stacks
    for figure, unit in FIGURES.items():
        ours, theirs = lite.values.get(figure), real.values.get(figure)
        if not ours or not theirs:
            if ours or theirs:
                missing = 'ros2lite' if not ours else 'real rclpy'
                print(f'vs_rclpy: {figure}: no result on {missing}', file=sys.stderr)
            continue
        a, b = statistics.median(ours), statistics.median(theirs)
        report(f'vs_rclpy_{figure}', a, unit, a / b if b else float('nan'))
        report(f'vs_rclpy_{figure}_real_rclpy', b, unit, 1.0)


BENCHES = {'vs_rclpy': bench_vs_rclpy}
