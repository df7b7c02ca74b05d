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
