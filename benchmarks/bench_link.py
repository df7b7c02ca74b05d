"""A link like Wi-Fi, for real: two network namespaces joined by a veth pair, each with a
ros2lite daemon, meshed (`--connect`), the link impaired (2 % loss, 20 Mbit/s, 30 ms delay
where the kernel has `tc netem`), then cut for `CUT` s.

In namespace A a node publishes a counter (reliable, KEEP_ALL) at `RATE` Hz; in namespace B a
reliable and a best-effort subscriber node, `topic echo`, `topic hz` and `bag record` take
it, and once the publisher is done `param get` and `service call` ask the publisher's node
across the link. Numbers: messages each receiver misses, how soon after the link is back
the counter flows again (`link_cut_recovery`), whether the bag is whole.

Needs root, `ip` (iproute2) and `tc`; loss falls back to an nftables rule (`nft`) and the
delay is left out where `netem` is missing (the output says which). Where namespaces cannot
be made at all, :class:`Unavailable` says why in one line (the test skips with it).
"""

from __future__ import annotations

import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from contextlib import ExitStack, contextmanager
from dataclasses import dataclass, field
from pathlib import Path

from common import report

COUNT = 1600
RATE = 200.0
CUT = 5.0
CUT_AFTER = 2.5  # seconds of publishing before the cut
PORT = 7447
TOPIC = '/link_counter'
LOSS_2_PERCENT = ('numgen', 'random', 'mod', '1000', '<', '20', 'drop')
LIST_PARAMETERS = ('/link_counter/list_parameters', 'rcl_interfaces/srv/ListParameters')

PUBLISHER = '''
import sys, time
import ros2lite
from ros2lite.interfaces import get_interface
from ros2lite.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy
Int64 = get_interface("std_msgs/msg/Int64")
ros2lite.init([])
node = ros2lite.Node("link_counter")
qos = QoSProfile(history=HistoryPolicy.KEEP_ALL, reliability=ReliabilityPolicy.RELIABLE)
pub = node.create_publisher(Int64, sys.argv[1], qos)
count, rate, subscribers = int(sys.argv[2]), float(sys.argv[3]), int(sys.argv[4])
deadline = time.monotonic() + 60
while pub.get_subscription_count() < subscribers and time.monotonic() < deadline:
    time.sleep(0.05)
time.sleep(0.5)
print("publishing", flush=True)
start = time.monotonic()
for i in range(count):
    pub.publish(Int64(data=i))
    time.sleep(max(0.0, start + (i + 1) / rate - time.monotonic()))
print("done", flush=True)
ros2lite.spin(node)  # its parameter services answer across the link
'''

SUBSCRIBER = '''
import sys, time
import ros2lite
from ros2lite.interfaces import get_interface
from ros2lite.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy
Int64 = get_interface("std_msgs/msg/Int64")
ros2lite.init([])
node = ros2lite.Node("link_" + sys.argv[2])
reliable = sys.argv[2] == "reliable"
policy = ReliabilityPolicy.RELIABLE if reliable else ReliabilityPolicy.BEST_EFFORT
qos = QoSProfile(history=HistoryPolicy.KEEP_ALL, reliability=policy)
node.create_subscription(
    Int64, sys.argv[1], lambda m: print(m.data, time.monotonic(), flush=True), qos)
try:
    ros2lite.spin(node)
except KeyboardInterrupt:
    pass
'''


class Unavailable(RuntimeError):
    """Network namespaces (or what impairs their link) cannot be had here; one line why."""


def _run(*cmd: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(cmd, capture_output=True, text=True, timeout=30)


@dataclass
class Link:
    """Namespaces ``a`` and ``b`` joined by a veth pair, addresses ``10.<x>.<y>.1/2``."""

    a: str
    b: str
    address_a: str
    address_b: str
    impairment: str = ''

    def ns(self, which: str) -> str:
        return self.a if which == 'a' else self.b

    def cut(self) -> None:
        _run('ip', '-n', self.a, 'link', 'set', 'lkv0', 'down')

    def restore(self) -> None:
        _run('ip', '-n', self.a, 'link', 'set', 'lkv0', 'up')


def _impair(link: Link) -> str:
    """netem on both ends (delay 30 ms, 2 % loss, 20 Mbit/s), else tbf for the rate and an
    nftables rule dropping 2 % of what arrives; returns what was applied."""
    netem = ['delay', '30ms', 'loss', '2%', 'rate', '20mbit']
    ends = ((link.a, 'lkv0'), (link.b, 'lkv1'))
    if all(
        _run(
            'ip', 'netns', 'exec', ns, 'tc', 'qdisc', 'add', 'dev', dev, 'root', 'netem', *netem
        ).returncode
        == 0
        for ns, dev in ends
    ):
        return 'netem delay 30ms loss 2% rate 20mbit'
    if shutil.which('nft') is None:
        raise Unavailable('no tc netem in this kernel and no nft (nftables) for the loss')
    for ns, dev in ends:
        _run('ip', 'netns', 'exec', ns, 'tc', 'qdisc', 'del', 'dev', dev, 'root')
        tbf = ['tbf', 'rate', '20mbit', 'burst', '32kbit', 'latency', '400ms']
        steps = [
            ['tc', 'qdisc', 'add', 'dev', dev, 'root', *tbf],
            ['nft', 'add', 'table', 'inet', 'lossy'],
            [
                'nft',
                'add',
                'chain',
                'inet',
                'lossy',
                'in',
                '{ type filter hook input priority 0; }',
            ],
            ['nft', 'add', 'rule', 'inet', 'lossy', 'in', 'iifname', dev, *LOSS_2_PERCENT],
        ]
        for step in steps:
            done = _run('ip', 'netns', 'exec', ns, *step)
            if done.returncode != 0:
                raise Unavailable(
                    f'cannot impair the link: {" ".join(step)}: {done.stderr.strip()}'
                )
    return 'nft loss 2% + tbf rate 20mbit (no netem in this kernel: no delay)'


@contextmanager
def namespaces() -> Iterator[Link]:
    """The two namespaces and their impaired link, removed on leaving."""
    if os.geteuid() != 0:
        raise Unavailable('network namespaces need root')
    if shutil.which('ip') is None or shutil.which('tc') is None:
        raise Unavailable('ip and tc (iproute2) are not installed')
    tag = f'{os.getpid() % 10000}{random.randint(0, 99):02d}'
    x, y = random.randint(16, 31), random.randint(0, 255)
    link = Link(f'lka{tag}', f'lkb{tag}', f'172.{x}.{y}.1', f'172.{x}.{y}.2')
    try:
        made = _run('ip', 'netns', 'add', link.a)
        if made.returncode != 0:
            raise Unavailable(f'cannot create a network namespace: {made.stderr.strip()}')
        steps = [
            ['ip', 'netns', 'add', link.b],
            ['ip', 'link', 'add', f'lk{tag}a', 'type', 'veth', 'peer', 'name', f'lk{tag}b'],
            ['ip', 'link', 'set', f'lk{tag}a', 'netns', link.a, 'name', 'lkv0'],
            ['ip', 'link', 'set', f'lk{tag}b', 'netns', link.b, 'name', 'lkv1'],
            ['ip', '-n', link.a, 'addr', 'add', f'{link.address_a}/24', 'dev', 'lkv0'],
            ['ip', '-n', link.b, 'addr', 'add', f'{link.address_b}/24', 'dev', 'lkv1'],
            ['ip', '-n', link.a, 'link', 'set', 'lkv0', 'up'],
            ['ip', '-n', link.b, 'link', 'set', 'lkv1', 'up'],
            ['ip', '-n', link.a, 'link', 'set', 'lo', 'up'],
            ['ip', '-n', link.b, 'link', 'set', 'lo', 'up'],
        ]
        for step in steps:
            done = _run(*step)
            if done.returncode != 0:
                raise Unavailable(
                    f'cannot set up the link: {" ".join(step)}: {done.stderr.strip()}'
                )
        link.impairment = _impair(link)
        yield link
    finally:
        for ns in (link.a, link.b):
            _run('ip', 'netns', 'del', ns)  # its veth end goes with it


@dataclass
class Outcome:
    """What crossed the link."""

    impairment: str
    published: int
    received: dict[str, set[int]] = field(default_factory=dict)
    recovery: float = -1.0  # s from the link's return to the next reliable message
    bag: int = -1  # distinct counter values in the recorded bag
    hz_after_cut: bool = False
    param_get: str = ''
    service_call: bool = False

    def missing(self, who: str) -> int:
        return self.published - len(self.received.get(who, set()))


class _Process:
    def __init__(self, link: Link, which: str, env: dict[str, str], args: list[str]) -> None:
        self.proc = subprocess.Popen(
            ['ip', 'netns', 'exec', link.ns(which), *args],
            env=env,
            text=True,
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
        )

    def stop(self, sig: int = signal.SIGINT) -> tuple[str, str]:
        if self.proc.poll() is None:
            self.proc.send_signal(sig)
        try:
            return self.proc.communicate(timeout=20)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            return self.proc.communicate()


def _arrivals(out: str) -> list[tuple[int, float]]:
    pairs = []
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 2 and parts[0].isdigit():
            pairs.append((int(parts[0]), float(parts[1])))
    return pairs


def cross(workdir: Path, *, count: int = COUNT, rate: float = RATE, cut: float = CUT) -> Outcome:
    """The whole run (module doc); raises Unavailable where it cannot be set up."""
    cli = [sys.executable, '-m', 'ros2lite']
    with namespaces() as link, ExitStack() as stack:
        base = {k: v for k, v in os.environ.items() if not k.startswith(('ROS_SEC', 'ZENOH_'))}
        base.update(ROS_DOMAIN_ID=str(random.randint(100, 232)), ROS2LITE_NO_DAEMON='1')
        base['PYTHONUNBUFFERED'] = '1'
        env = {}
        for which, address in (('a', link.address_a), ('b', link.address_b)):
            runtime = workdir / f'run_{which}'
            runtime.mkdir(mode=0o700)
            env[which] = {
                **base,
                'ROS2LITE_ROUTER': f'tcp/{address}:{PORT}',
                'XDG_RUNTIME_DIR': str(runtime),
            }
        started: list[_Process] = []
        stack.callback(lambda: [p.stop(signal.SIGKILL) for p in started])

        def start(which: str, args: list[str]) -> _Process:
            process = _Process(link, which, env[which], args)
            started.append(process)
            return process

        daemon = [sys.executable, '-m', 'ros2lite.daemon', '--foreground', '--router']
        start('a', [*daemon, env['a']['ROS2LITE_ROUTER']])
        start('b', [*daemon, env['b']['ROS2LITE_ROUTER'], '--connect', env['a']['ROS2LITE_ROUTER']])
        for which in 'ab':
            deadline = time.monotonic() + 20
            probe = ['ip', 'netns', 'exec', link.ns(which), *cli, 'daemon', 'status']
            while (
                'ros2lite daemon'
                not in subprocess.run(probe, env=env[which], capture_output=True, text=True).stdout
            ):
                if time.monotonic() > deadline:
                    raise RuntimeError(f'no daemon came up in namespace {which}')
                time.sleep(0.2)
        reliable = start('b', [sys.executable, '-c', SUBSCRIBER, TOPIC, 'reliable'])
        best_effort = start('b', [sys.executable, '-c', SUBSCRIBER, TOPIC, 'best_effort'])
        qos = ['--qos-reliability', 'reliable', '--qos-history', 'keep_all', '--qos-depth', '1000']
        echo = start('b', [*cli, 'topic', 'echo', TOPIC, 'std_msgs/msg/Int64', *qos])
        hz = start('b', [*cli, 'topic', 'hz', TOPIC])
        bag = workdir / 'bag'
        recorder = start('b', [*cli, 'bag', 'record', '--topics', TOPIC, '-o', str(bag)])
        publisher = start('a', [sys.executable, '-c', PUBLISHER, TOPIC, str(count), str(rate), '4'])
        assert publisher.proc.stdout is not None
        if publisher.proc.stdout.readline().strip() != 'publishing':
            raise RuntimeError('the publisher never saw its subscribers across the link')
        time.sleep(CUT_AFTER)
        link.cut()
        time.sleep(cut)
        link.restore()
        restored = time.monotonic()
        publisher.proc.stdout.readline()  # done
        time.sleep(2.0)
        outcome = Outcome(link.impairment, count)
        hz_out, _ = hz.stop()
        outcome.hz_after_cut = 'average rate' in hz_out
        node = '/link_counter'
        got = subprocess.run(
            ['ip', 'netns', 'exec', link.ns('b'), *cli, 'param', 'get', node, 'use_sim_time'],
            env=env['b'],
            capture_output=True,
            text=True,
            timeout=30,
        )
        outcome.param_get = got.stdout.strip() or got.stderr.strip()
        call = subprocess.run(
            ['ip', 'netns', 'exec', link.ns('b'), *cli, 'service', 'call', *LIST_PARAMETERS],
            env=env['b'],
            capture_output=True,
            text=True,
            timeout=30,
        )
        outcome.service_call = call.returncode == 0 and 'use_sim_time' in call.stdout
        for name, process in (('reliable', reliable), ('best_effort', best_effort)):
            arrivals = _arrivals(process.stop()[0])
            outcome.received[name] = {n for n, _ in arrivals}
            if name == 'reliable':
                after = [t for _, t in arrivals if t >= restored]
                outcome.recovery = min(after) - restored if after else -1.0
        echo_out, _ = echo.stop()
        outcome.received['echo'] = {
            int(line[6:]) for line in echo_out.splitlines() if line.startswith('data: ')
        }
        recorder.stop()
    from ros2lite.bag import Reader

    with Reader(bag) as reader:
        outcome.bag = len({m.data for _, m, _ in reader.messages()})
    return outcome


def bench_link() -> None:
    with tempfile.TemporaryDirectory() as workdir:
        try:
            outcome = cross(Path(workdir))
        except Unavailable as exc:
            print(f'link skipped: {exc}', flush=True)
            return
    print(f'link impairment: {outcome.impairment}, cut {CUT:g} s', flush=True)
    for who in ('reliable', 'echo', 'best_effort'):
        report(f'link_{who}_lost', outcome.missing(who), 'msgs', outcome.missing(who) / COUNT)
    report('link_bag_lost', COUNT - outcome.bag, 'msgs', (COUNT - outcome.bag) / COUNT)
    report('link_cut_recovery', outcome.recovery, 's', outcome.recovery / CUT)


BENCHES = {'link': bench_link}
