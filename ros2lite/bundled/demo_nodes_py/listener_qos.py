"""`listener_qos`: `listener` with a chosen reliability — best effort (sensor data QoS)
unless `--reliable` — that stops after `-n/--number_of_cycles` turns of its spin loop."""

from __future__ import annotations

import sys

from ros2lite.bundled.demo_nodes_py.listener import Listener
from ros2lite.bundled.demo_nodes_py.talker_qos import qos_demo_options, spin_cycles
from ros2lite.bundled.runner import run_main
from ros2lite.qos import QoSProfile, ReliabilityPolicy


class ListenerQos(Listener):
    """Says which reliability it uses, then logs what arrives on `chatter`."""

    def __init__(self, qos_profile: QoSProfile) -> None:
        super().__init__('listener_qos', qos_profile)
        reliable = qos_profile.reliability == ReliabilityPolicy.RELIABLE
        self.get_logger().info('Reliable listener' if reliable else 'Best effort listener')


def main(args: list[str] | None = None) -> int:
    """`listener_qos`'s entry point."""
    qos, cycles = qos_demo_options(
        sys.argv[1:] if args is None else args, 'max number of spin_once iterations'
    )
    return run_main(lambda: spin_cycles(lambda: ListenerQos(qos), cycles), args)


if __name__ == '__main__':
    raise SystemExit(main())
