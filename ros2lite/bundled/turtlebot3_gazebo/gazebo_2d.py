"""`gazebo_2d`: ros2lite's 2D simulator node with one robot, the node the launch files start
where Gazebo's server and the robot's spawner would run.

Parameters (`-p name:=value`, or a launch file's `parameters=`): robot_model (burger, waffle,
waffle_pi; default $TURTLEBOT3_MODEL), world (a bundled world's name, a map YAML or a .world
file), x_pose, y_pose, yaw, real_time_factor (0: as fast as possible), odom_noise,
publish_robot_state (publish /robot_description and the fixed frames when no
robot_state_publisher runs), seed.
"""

from __future__ import annotations

import os

from ros2lite.bundled.runner import run_main


def main(args: list[str] | None = None) -> int:
    """Run the simulator until Ctrl-C."""

    def body() -> None:
        import ros2lite
        from ros2lite.sim.node import Settings, SimNode

        model = os.environ.get('TURTLEBOT3_MODEL', 'burger') or 'burger'
        node = SimNode(Settings(robot_model=model))
        try:
            ros2lite.spin(node)
        finally:
            node.destroy_node()

    return run_main(body, args)


if __name__ == '__main__':
    raise SystemExit(main())
