"""The six standard parameter services every node offers under `~/`, answered as rclpy does:
an unknown name empties the whole reply (get/describe/types); an undeclared parameter in a set
is a failed result whose reason is the exception's message."""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any, TypeVar

from ros2lite.exceptions import ParameterNotDeclaredException, ParameterUninitializedException
from ros2lite.parameter import Parameter
from ros2lite.parameters.store import result

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces import srv
    from ros2lite.msgs.rcl_interfaces.msg import Parameter as ParameterMsg
    from ros2lite.msgs.rcl_interfaces.msg import SetParametersResult
    from ros2lite.node_interface import NodeInterface
    from ros2lite.service import Service

SERVICES = (
    "describe_parameters",
    "get_parameters",
    "get_parameter_types",
    "list_parameters",
    "set_parameters",
    "set_parameters_atomically",
)
TYPES = {
    "describe_parameters": "DescribeParameters",
    "get_parameters": "GetParameters",
    "get_parameter_types": "GetParameterTypes",
    "list_parameters": "ListParameters",
    "set_parameters": "SetParameters",
    "set_parameters_atomically": "SetParametersAtomically",
}

_T = TypeVar('_T')


def _all_or_none(
    names: Iterable[str],
    lookup: Callable[[str], _T],
    errors: type[Exception] | tuple[type[Exception], ...],
) -> list[_T]:
    """`lookup` of every name, or an empty list when one fails with `errors` (what rclpy's
    parameter services answer for a name that is not there)."""
    try:
        return [lookup(n) for n in names]
    except errors:
        return []


class ParameterService:
    """Creates the services on `node` (names relative to the node: `<node>/<service>`)."""

    def __init__(self, node: NodeInterface) -> None:
        from ros2lite.qos import qos_profile_parameters

        self._node = node
        self.services: list[Service[Any, Any]] = [
            node.create_service(
                f"rcl_interfaces/srv/{TYPES[name]}",
                f"{node.get_name()}/{name}",
                getattr(self, f"_{name}"),
                qos_profile=qos_profile_parameters,
            )
            for name in SERVICES
        ]

    def _describe_parameters(
        self, request: srv.DescribeParameters.Request, response: srv.DescribeParameters.Response
    ) -> srv.DescribeParameters.Response:
        response.descriptors = _all_or_none(
            request.names, self._node.describe_parameter, ParameterNotDeclaredException
        )
        return response

    def _get_parameters(
        self, request: srv.GetParameters.Request, response: srv.GetParameters.Response
    ) -> srv.GetParameters.Response:
        response.values = _all_or_none(
            request.names,
            lambda n: self._node.get_parameter(n).get_parameter_value(),
            (ParameterNotDeclaredException, ParameterUninitializedException),
        )
        return response

    def _get_parameter_types(
        self, request: srv.GetParameterTypes.Request, response: srv.GetParameterTypes.Response
    ) -> srv.GetParameterTypes.Response:
        response.types = _all_or_none(
            request.names,
            lambda n: self._node.get_parameter_type(n).value,
            ParameterNotDeclaredException,
        )
        return response

    def _list_parameters(
        self, request: srv.ListParameters.Request, response: srv.ListParameters.Response
    ) -> srv.ListParameters.Response:
        # a bad request gets the default (empty) result
        with contextlib.suppress(TypeError, ValueError):
            response.result = self._node.list_parameters(list(request.prefixes), int(request.depth))
        return response

    def _set_parameters(
        self, request: srv.SetParameters.Request, response: srv.SetParameters.Response
    ) -> srv.SetParameters.Response:
        response.results = [self._set([p]) for p in request.parameters]
        return response

    def _set_parameters_atomically(
        self,
        request: srv.SetParametersAtomically.Request,
        response: srv.SetParametersAtomically.Response,
    ) -> srv.SetParametersAtomically.Response:
        response.result = self._set(list(request.parameters))
        return response

    def _set(self, messages: list[ParameterMsg]) -> SetParametersResult:
        """Set atomically; undeclared names and malformed values are failed results."""
        try:
            params = [Parameter.from_parameter_msg(m) for m in messages]
            outcome = self._node.set_parameters_atomically(params)
        except (ParameterNotDeclaredException, TypeError, ValueError) as e:
            return result(False, str(e))
        return outcome

    def destroy(self) -> None:
        """Withdraw the six services."""
        for service in self.services:
            self._node.destroy_service(service)
        self.services.clear()
