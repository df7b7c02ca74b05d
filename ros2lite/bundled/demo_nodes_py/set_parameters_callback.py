"""`set_parameters_callback`: the three parameter callbacks at work on `param1` and `param2`
(doubles, 0.0). Setting `param1` also sets `param2` to 4.0 (pre-set), both are accepted with
a reason naming them (on-set), and the node keeps its own copy of each new value (post-set):

    ros2lite param set /set_parameters_callback param1 1.0
    ros2lite param get /set_parameters_callback param2      # 4.0
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ros2lite.bundled.runner import run_node
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from ros2lite.parameter import Parameter

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces.msg import SetParametersResult


class SetParametersCallback(Node):
    """Tracks `param1` and `param2` through pre-, on- and post-set callbacks."""

    def __init__(self) -> None:
        super().__init__('set_parameters_callback')
        self.internal_tracked_param_1 = self.declare_parameter('param1', 0.0).value
        self.internal_tracked_param_2 = self.declare_parameter('param2', 0.0).value
        self.add_pre_set_parameters_callback(self.pre_set)
        self.add_on_set_parameters_callback(self.on_set)
        self.add_post_set_parameters_callback(self.post_set)

    def pre_set(self, parameters: list[Parameter]) -> list[Parameter]:
        """A set of `param1` brings `param2 = 4.0` with it."""
        extra = [Parameter('param2', Parameter.Type.DOUBLE, 4.0)]
        return parameters + extra * any(p.name == 'param1' for p in parameters)

    def on_set(self, parameters: list[Parameter]) -> SetParametersResult:
        """Accept both, saying which was seen last."""
        result: SetParametersResult = get_interface('rcl_interfaces/msg/SetParametersResult')()
        for param in parameters:
            if param.name in ('param1', 'param2'):
                result.successful = True
                result.reason = f'success {param.name}'
        return result

    def post_set(self, parameters: list[Parameter]) -> None:
        """Keep the node's own copies in step."""
        for param in parameters:
            if param.name == 'param1':
                self.internal_tracked_param_1 = param.value
            elif param.name == 'param2':
                self.internal_tracked_param_2 = param.value


def main(args: list[str] | None = None) -> int:
    """`set_parameters_callback`'s entry point."""
    return run_node(SetParametersCallback, args)


if __name__ == '__main__':
    raise SystemExit(main())
