"""`gazebo_2d`: ros2lite's 2D simulator with the Jackal (parameters as turtlebot3_gazebo's
`gazebo_2d`: world, x_pose, y_pose, yaw, real_time_factor, ...)."""

from __future__ import annotations

from ros2lite.bundled.simulator import run_simulator


def main(args: list[str] | None = None) -> int:
    """Run the Jackal simulator until Ctrl-C."""
    return run_simulator('jackal', args)


if __name__ == '__main__':
    raise SystemExit(main())
