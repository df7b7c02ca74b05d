"""`create`: the new Gazebo's spawner, its command line (`-name N` and one of `-topic T`,
`-file F`, `-string XML`, `-param P`; `-x -y -z -R -P -Y`, `-world`, `-allow_renaming`),
adding the robot to ros2lite's running 2D world. Only the planar part of the pose counts."""

from __future__ import annotations

import argparse

from ros2lite.bundled.spawner import Order, run_spawner


def _parse(argv: list[str]) -> Order:
    parser = argparse.ArgumentParser(prog='create', description='Spawn a robot into the 2D world')
    parser.add_argument('-name', default='', help='name of the entity (default: the robot name)')
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument('-file', default='', help='load the URDF from this file')
    source.add_argument('-topic', default='', help='load the URDF from this topic')
    source.add_argument('-string', default='', help='the URDF itself')
    source.add_argument('-param', default='', help='load the URDF from this node parameter')
    parser.add_argument('-world', default='', help='(accepted; one world here)')
    parser.add_argument('-allow_renaming', default='false', help='(accepted)')
    for axis in ('x', 'y', 'z', 'R', 'P', 'Y'):
        parser.add_argument(f'-{axis}', type=float, default=0.0, help=f'initial {axis}')
    options = parser.parse_args(argv)
    return Order(
        name=options.name,
        topic=options.topic,
        file=options.file,
        text=options.string,
        param=options.param,
        x=options.x,
        y=options.y,
        yaw=options.Y,
    )


def main(args: list[str] | None = None) -> int:
    """Spawn the robot the command line names; 0 once the world has it."""
    return run_spawner('ros_gz_sim', _parse, args)


if __name__ == '__main__':
    raise SystemExit(main())
