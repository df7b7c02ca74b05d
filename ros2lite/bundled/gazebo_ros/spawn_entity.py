"""`spawn_entity.py`: Gazebo Classic's spawner, its command line (`-entity NAME` and one of
`-topic T`, `-file F`, `-stdin`; `-x -y -z -R -P -Y`, `-robot_namespace`, `-timeout`), adding
the robot to ros2lite's running 2D world. Only the planar part of the pose counts (x, y, Y)."""

from __future__ import annotations

import argparse
import sys

from ros2lite.bundled.spawner import Order, run_spawner


def _parse(argv: list[str]) -> Order:
    parser = argparse.ArgumentParser(
        prog='spawn_entity.py', description='Spawn a robot into the 2D world'
    )
    parser.add_argument('-entity', required=True, help='name of the entity to spawn')
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument('-file', default='', help='load the URDF from this file')
    source.add_argument('-topic', default='', help='load the URDF from this topic')
    source.add_argument('-stdin', action='store_true', help='load the URDF from stdin')
    source.add_argument('-database', default='', help='(a Gazebo model database: not here)')
    parser.add_argument('-robot_namespace', default='', help="namespace of the robot's topics")
    parser.add_argument('-timeout', type=float, default=30.0, help='seconds to wait for the world')
    for axis in ('x', 'y', 'z', 'R', 'P', 'Y'):
        parser.add_argument(f'-{axis}', type=float, default=0.0, help=f'initial {axis}')
    for ignored in ('-reference_frame', '-gazebo_namespace', '-spawn_service_timeout'):
        parser.add_argument(ignored, default='', help='(accepted; one world here)')
    parser.add_argument('-unpause', action='store_true', help='(accepted; the world runs)')
    options = parser.parse_args(argv)
    if options.database:
        parser.error('-database: the 2D world has no Gazebo model database; use -file or -topic')
    return Order(
        name=options.entity,
        topic=options.topic,
        file=options.file,
        text=sys.stdin.read() if options.stdin else '',
        x=options.x,
        y=options.y,
        yaw=options.Y,
        namespace=options.robot_namespace,
        timeout=options.timeout,
    )


def main(args: list[str] | None = None) -> int:
    """Spawn the robot the command line names; 0 once the world has it."""
    return run_spawner('spawn_entity', _parse, args)


if __name__ == '__main__':
    raise SystemExit(main())
