"""`talker_qos`: `talker` with a chosen reliability — best effort (sensor data QoS) unless
`--reliable` — that stops after `-n/--number_of_cycles` turns of its spin loop (default 20)."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable

import ros2lite
from ros2lite.bundled.demo_nodes_py.talker import Talker
from ros2lite.bundled.runner import run_main
from ros2lite.node import Node
from ros2lite.qos import QoSProfile, ReliabilityPolicy, qos_profile_sensor_data
from ros2lite.runtime.arguments import remove_ros_args


def qos_demo_options(argv: list[str], cycles_help: str) -> tuple[QoSProfile, int]:
    """The QoS profile and cycle count the two QoS demos take from their own arguments
    (exits with usage on bad ones, as argparse does)."""
    parser = argparse.ArgumentParser(formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument(
        '--reliable', action='store_true', default=False, help='set qos profile to reliable'
    )
    parser.add_argument('-n', '--number_of_cycles', type=int, default=20, help=cycles_help)
    options = parser.parse_args(remove_ros_args(argv))
    if options.reliable:
        return QoSProfile(
            depth=10, reliability=ReliabilityPolicy.RELIABLE
        ), options.number_of_cycles
    return qos_profile_sensor_data, options.number_of_cycles


def spin_cycles(make_node: Callable[[], Node], cycles: int) -> None:
    """Build the node and let it do `cycles` pieces of work, then destroy it."""
    node = make_node()
    try:
        done = 0
        while ros2lite.ok() and done < cycles:
            ros2lite.spin_once(node)
            done += 1
    finally:
        node.destroy_node()


class TalkerQos(Talker):
    """Says which reliability it uses, then publishes `Hello World: N` once a second."""

    def __init__(self, qos_profile: QoSProfile) -> None:
        super().__init__('talker_qos', qos_profile)
        reliable = qos_profile.reliability == ReliabilityPolicy.RELIABLE
        self.get_logger().info('Reliable talker' if reliable else 'Best effort talker')


def main(args: list[str] | None = None) -> int:
    """`talker_qos`'s entry point."""
    qos, cycles = qos_demo_options(
        sys.argv[1:] if args is None else args, 'number of sending attempts'
    )
    return run_main(lambda: spin_cycles(lambda: TalkerQos(qos), cycles), args)


if __name__ == '__main__':
    raise SystemExit(main())
