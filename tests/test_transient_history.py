"""A transient-local publisher's history honours its lifespan (R5-G4): a late joiner gets
no expired sample, and what comes later is kept again."""

from __future__ import annotations

from typing import Any

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from ros2lite.qos import DurabilityPolicy, QoSProfile
from tests.spinning import spin_for, spin_until

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


DEPTH = 1000
BOUND = 1 << 20  # the publisher's HISTORY_BYTES here: 1 MiB, so 40 samples of 100 kB pass it
BYTES_PUBLISHER = f"""
import sys
import ros2lite
import ros2lite.transport.history as history
from ros2lite.node import Node
from ros2lite.qos import DurabilityPolicy, QoSProfile
from ros2lite.msgs.std_msgs.msg import String

history.HISTORY_BYTES = {BOUND}
ros2lite.init()
node = Node('bytes_pub')
pub = node.create_publisher(
    String, 'bytes', QoSProfile(depth={DEPTH}, durability=DurabilityPolicy.TRANSIENT_LOCAL)
)
print('ready', flush=True)
for line in sys.stdin:
    n, size = line.split()
    pub.publish(String(data=n + ':' + 'x' * int(size)))
    print('sent', n, flush=True)
"""


def test_the_history_is_bounded_in_bytes_and_live_subscribers_get_everything_in_order(
    ros_context: Any, processes: Any
) -> None:
    """R5-G4: depth 1000 of 100 kB samples would keep 4 MB; the history keeps at most the
    bound (1 MiB here) and always the newest sample, while a live subscriber gets every
    sample, once and in order, across the history's new starts."""
    import subprocess

    proc = processes.python(BYTES_PUBLISHER, stdin=subprocess.PIPE)
    assert proc.stdout.readline().strip() == 'ready'
    qos = QoSProfile(depth=DEPTH, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    node = Node('bytes_sub', context=ros_context)
    live: list[str] = []
    node.create_subscription('std_msgs/msg/String', 'bytes', lambda m: live.append(m.data), qos)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    spin_until(executor, lambda: node.count_publishers('bytes') == 1, timeout=10)
    sizes = [10, 20, 30] + [100_000] * 40 + [40]
    for n, size in enumerate(sizes):
        proc.stdin.write(f'{n} {size}\n')
        proc.stdin.flush()
        assert proc.stdout.readline().split() == ['sent', str(n)]
        if n == 0:
            # the graph showing the publisher is not the data path joined: had the history
            # started anew before this subscriber's history query came, the first samples
            # would be gone for it, rightly (a loaded full suite saw that once)
            spin_until(executor, lambda: live, timeout=10)
    spin_until(executor, lambda: len(live) == len(sizes), timeout=30)
    spin_for(executor, 0.5)  # nothing twice
    assert [int(d.split(':')[0]) for d in live] == list(range(len(sizes)))

    late = Node('bytes_late', context=ros_context)
    kept: list[str] = []
    late.create_subscription('std_msgs/msg/String', 'bytes', lambda m: kept.append(m.data), qos)
    executor.add_node(late)
    spin_until(executor, lambda: kept and kept[-1].startswith(f'{len(sizes) - 1}:'), timeout=10)
    spin_for(executor, 0.5)  # the history comes in one answer: nothing more is on its way
    numbers = [int(d.split(':')[0]) for d in kept]
    assert numbers == sorted(numbers) and numbers[-1] == len(sizes) - 1
    assert sum(len(d) for d in kept) <= BOUND, numbers  # bounded in bytes
    assert len(kept) >= 5, numbers  # and still a history, not only the newest sample


def test_a_depth_one_history_is_not_made_anew_for_every_large_sample() -> None:
    """With depth 1 the cache holds only the newest sample anyway: a sample larger than the
    byte bound replaces it without the advanced publisher being undeclared and declared
    again per message (which it was, every put); at depth 3 the history starts anew only
    when older samples would stay beside the new one past the bound."""
    from ros2lite.transport.history import HistoryBoundedPublisher

    made: list[list[int]] = []

    class Fake:
        def __init__(self) -> None:
            self.sizes: list[int] = []
            made.append(self.sizes)

        def put(self, payload: bytes, attachment: bytes | None = None) -> None:
            self.sizes.append(len(payload))

        def undeclare(self) -> None:
            pass

    one = HistoryBoundedPublisher(Fake, None, depth=1, limit=100)  # type: ignore[arg-type]
    for _ in range(5):
        one.put(bytes(150))
    assert made == [[150] * 5]
    made.clear()
    three = HistoryBoundedPublisher(Fake, None, depth=3, limit=100)  # type: ignore[arg-type]
    for size in (40, 40, 40, 150, 150, 10):
        three.put(bytes(size))
    # 40+40+40 > 100 starts anew at the third; 150 beside a 40 does too; 150 beside 150 too;
    # 10 beside 150 too: each time what stays would pass the bound
    assert made == [[40, 40], [40], [150], [150], [10]]
