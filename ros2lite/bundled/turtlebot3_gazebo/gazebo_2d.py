"""`gazebo_2d`: ros2lite's 2D simulator node with one robot, the node the launch files start
where Gazebo's server and the robot's spawner would run.

Parameters (`-p name:=value`, or a launch file's `parameters=`): robot_model (burger, waffle,
waffle_pi; default $TURTLEBOT3_MODEL), world (a bundled world's name, a map YAML or a .world
file), x_pose, y_pose, yaw, real_time_factor (0: as fast as possible), odom_noise,
publish_robot_state (publish /robot_description and the fixed frames when no
robot_state_publisher runs), seed, scan_rate.
"""

from __future__ import annotations

import os

from ros2lite.bundled.simulator import run_simulator


def main(args: list[str] | None = None) -> int:
    """Run the simulator with $TURTLEBOT3_MODEL (burger when unset) until Ctrl-C."""
    return run_simulator(os.environ.get('TURTLEBOT3_MODEL', 'burger') or 'burger', args)


if __name__ == '__main__':
    raise SystemExit(main())
