"""`introspection_service`: the `add_two_ints` server whose introspection follows its
`service_configure_introspection` parameter (`disabled`, `metadata` or `contents`; change it
at run time with `ros2lite param set`). Watch with `ros2lite service echo /add_two_ints`."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from ros2lite.bundled.demo_nodes_py.add_two_ints_server import AddTwoIntsServer
from ros2lite.bundled.runner import run_node
from ros2lite.node import Node
from ros2lite.parameter import Parameter
from ros2lite.qos import qos_profile_system_default
from ros2lite.service_introspection import state_from_name

if TYPE_CHECKING:
    from ros2lite.clock import Clock
    from ros2lite.msgs.rcl_interfaces.msg import SetParametersResult
    from ros2lite.qos import QoSProfile
    from ros2lite.service_introspection import ServiceIntrospectionState


def follow_parameter(
    node: Node,
    name: str,
    configure: Callable[[Clock, QoSProfile, ServiceIntrospectionState], object],
) -> None:
    """Check every new value of the string parameter `name` and reconfigure introspection
    with it once set (what both introspection demos do)."""
    from ros2lite.interfaces import get_interface

    result_type: type[SetParametersResult] = get_interface('rcl_interfaces/msg/SetParametersResult')

    def check(parameters: list[Parameter]) -> SetParametersResult:
        for param in parameters:
            if param.name != name:
                continue
            if param.type_ != Parameter.Type.STRING:
                return result_type(successful=False, reason='must be a string')
            try:
                state_from_name(param.value)
            except ValueError as e:
                return result_type(successful=False, reason=str(e))
        return result_type(successful=True)

    def apply(parameters: list[Parameter]) -> None:
        for param in parameters:
            if param.name == name:
                configure(
                    node.get_clock(), qos_profile_system_default, state_from_name(param.value)
                )

    node.add_on_set_parameters_callback(check)
    node.add_post_set_parameters_callback(apply)
    node.declare_parameter(name, 'disabled')


class IntrospectionServiceNode(AddTwoIntsServer):
    """Adds two integers; reports its requests and responses as its parameter says."""

    def __init__(self) -> None:
        super().__init__('introspection_service')
        follow_parameter(self, 'service_configure_introspection', self.srv.configure_introspection)


def main(args: list[str] | None = None) -> int:
    """`introspection_service`'s entry point."""
    return run_node(IntrospectionServiceNode, args)


if __name__ == '__main__':
    raise SystemExit(main())
