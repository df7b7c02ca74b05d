"""A transient-local publisher's history is bounded in bytes as well as depth (R5-G4: a
/rosout of 16 MB lines kept 1000 of them): samples over the per-sample share of
HISTORY_BYTES go out live but are not kept, so a late joiner gets only the small ones, a
live subscriber gets all of them in order, and the publisher's memory stays put."""

from __future__ import annotations

from typing import Any

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from ros2lite.qos import DurabilityPolicy, QoSProfile
from ros2lite.transport.session import HISTORY_BYTES
from tests.spinning import spin_for, spin_until

DEPTH = 1000
LARGEST_KEPT = HISTORY_BYTES // DEPTH
TL = QoSProfile(depth=DEPTH, durability=DurabilityPolicy.TRANSIENT_LOCAL)

PUBLISHER = f"""
import sys
import ros2lite
from ros2lite.node import Node
from ros2lite.qos import DurabilityPolicy, QoSProfile
from ros2lite.msgs.std_msgs.msg import String

ros2lite.init()
node = Node('hist_pub')
qos = QoSProfile(depth={DEPTH}, durability=DurabilityPolicy.TRANSIENT_LOCAL)
pub = node.create_publisher(String, 'hist', qos)
print('ready', flush=True)
for line in sys.stdin:
    n, size = line.split()
    pub.publish(String(data=n + ':' + 'x' * int(size)))
    status = open('/proc/self/status').read()
    rss = int(status.split('VmRSS:')[1].split()[0])
    print('sent', n, rss, flush=True)
"""


def _send(proc: Any, n: int, size: int) -> int:
    proc.stdin.write(f'{n} {size}\n')
    proc.stdin.flush()
    words = proc.stdout.readline().split()
    assert words[:2] == ['sent', str(n)], words
    return int(words[2])


def test_large_samples_go_live_but_stay_out_of_the_history(
    ros_context: Any, processes: Any
) -> None:
    import subprocess

    proc = processes.python(PUBLISHER, stdin=subprocess.PIPE)
    assert proc.stdout.readline().strip() == 'ready'
    node = Node('hist_sub', context=ros_context)
    live: list[str] = []
    node.create_subscription('std_msgs/msg/String', 'hist', lambda m: live.append(m.data), TL)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    spin_until(executor, lambda: node.count_publishers('hist') == 1, timeout=10)
    big = LARGEST_KEPT + 1
    sizes = [10, big, 20, big, 30] + [big] * 40
    rss = [_send(proc, n, size) for n, size in enumerate(sizes)]
    spin_until(executor, lambda: len(live) == len(sizes), timeout=30)
    assert [int(d.split(':')[0]) for d in live] == list(range(len(sizes)))  # in order
    # 40 samples over 64 KiB each would be 2.6 MB of history: the publisher holds none
    assert rss[-1] - rss[5] < 2_000, rss

    late = Node('hist_late', context=ros_context)
    kept: list[str] = []
    late.create_subscription('std_msgs/msg/String', 'hist', lambda m: kept.append(m.data), TL)
    executor.add_node(late)
    spin_until(executor, lambda: len(kept) >= 3, timeout=10)
    spin_for(executor, 0.5)  # the history comes in one answer: nothing more is on its way
    assert [d.split(':')[0] for d in kept] == ['0', '2', '4']


SPAN = 3  # seconds: the early joiner must be in within it, even on a loaded machine
LIFESPAN_PUBLISHER = """
import sys
SPAN = @SPAN@
import ros2lite
from ros2lite.duration import Duration
from ros2lite.node import Node
from ros2lite.qos import DurabilityPolicy, QoSProfile
from ros2lite.msgs.std_msgs.msg import String

ros2lite.init()
node = Node('span_pub')
qos = QoSProfile(
    depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL, lifespan=Duration(seconds=SPAN)
)
pub = node.create_publisher(String, 'span', qos)
print('ready', flush=True)
for line in sys.stdin:
    pub.publish(String(data=line.strip()))
    print('sent', flush=True)
""".replace('@SPAN@', str(SPAN))


def test_a_late_joiner_gets_no_expired_sample(ros_context: Any, processes: Any) -> None:
    """Lifespan 3 s: joined within it, the history is there; joined after it, nothing is,
    and what is published later is kept again."""
    import subprocess
    import time

    proc = processes.python(LIFESPAN_PUBLISHER, stdin=subprocess.PIPE)
    assert proc.stdout.readline().strip() == 'ready'
    executor = SingleThreadedExecutor(context=ros_context)

    def join(name: str) -> list[str]:
        got: list[str] = []
        node = Node(name, context=ros_context)
        qos = QoSProfile(depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL)
        node.create_subscription('std_msgs/msg/String', 'span', lambda m: got.append(m.data), qos)
        executor.add_node(node)
        spin_until(executor, lambda: node.count_publishers('span') == 1, timeout=10)
        return got

    for word in ('a', 'b'):
        proc.stdin.write(word + '\n')
        proc.stdin.flush()
        assert proc.stdout.readline().strip() == 'sent'
    sent = time.monotonic()
    early = join('span_early')
    spin_until(executor, lambda: early == ['a', 'b'], timeout=10)
    spin_for(executor, max(0.0, sent + SPAN + 0.5 - time.monotonic()))  # past the lifespan
    late = join('span_late')
    spin_for(executor, 1.0)
    assert late == []
    proc.stdin.write('c\n')
    proc.stdin.flush()
    assert proc.stdout.readline().strip() == 'sent'
    later = join('span_later')
    spin_until(executor, lambda: later == ['c'], timeout=10)
    assert late == ['c'] and early == ['a', 'b', 'c']
