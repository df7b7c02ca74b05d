"""The body of every simulator executable (`turtlebot3_gazebo gazebo_2d`, `jackal_gazebo
gazebo_2d`, ...): ros2lite's 2D simulator node for a default robot, spun until Ctrl-C."""

from __future__ import annotations

from ros2lite.bundled.runner import run_main


def run_simulator(default_model: str, args: list[str] | None = None) -> int:
    """Run the simulator with `default_model` unless the `robot_model` parameter says else."""

    def body() -> None:
        import ros2lite
        from ros2lite.sim.node import Settings, SimNode

        node = SimNode(Settings(robot_model=default_model))
        try:
            ros2lite.spin(node)
        finally:
            node.destroy_node()

    return run_main(body, args)
