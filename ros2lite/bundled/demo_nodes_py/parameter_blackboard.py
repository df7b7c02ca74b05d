"""`parameter_blackboard`: a node that holds whatever parameters it is given or sent.

As ROS's demo: undeclared parameters are allowed and every override (`-p`, params files) is
declared at start-up, so `ros2lite param set/get/list/dump/load` can be tried on it.
"""

from __future__ import annotations

from ros2lite.bundled.runner import run_node
from ros2lite.node import Node


class ParameterBlackboard(Node):
    """A node that holds whatever parameters it is given or set."""

    def __init__(self) -> None:
        super().__init__(
            "parameter_blackboard",
            allow_undeclared_parameters=True,
            automatically_declare_parameters_from_overrides=True,
        )
        self.get_logger().info(
            "Parameter blackboard node named "
            f"'{self.get_fully_qualified_name()}' ready, and serving "
            "'{}' parameters already!".format(len(self.list_parameters([], 0).names))
        )


def main(args: list[str] | None = None) -> int:
    """`parameter_blackboard`'s entry point."""
    return run_node(ParameterBlackboard, args)


if __name__ == "__main__":
    raise SystemExit(main())
