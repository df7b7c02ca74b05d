"""The six standard parameter services every node offers under `~/`, answered as rclpy does:
an unknown name empties the whole reply (get/describe/types); an undeclared parameter in a set
is a failed result whose reason is the exception's message."""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, Protocol, TypeVar

from ros2lite.exceptions import ParameterNotDeclaredException, ParameterUninitializedException
from ros2lite.parameter import Parameter
from ros2lite.parameters.store import result

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces import srv
    from ros2lite.msgs.rcl_interfaces.msg import Parameter as ParameterMsg
    from ros2lite.msgs.rcl_interfaces.msg import SetParametersResult
    from ros2lite.node_interface import NodeInterface
    from ros2lite.service import Service

TYPES = {
    "describe_parameters": "DescribeParameters",
    "get_parameters": "GetParameters",
    "get_parameter_types": "GetParameterTypes",
    "list_parameters": "ListParameters",
    "set_parameters": "SetParameters",
    "set_parameters_atomically": "SetParametersAtomically",
}
SERVICES = tuple(TYPES)

_Response = TypeVar('_Response')


class _NamesRequest(Protocol):
    """What the get, describe and types requests share."""

    names: Sequence[str]


def _all_or_none(
    field: str,
    lookup: Callable[[str], object],
    errors: type[Exception] | tuple[type[Exception], ...],
) -> Callable[[_NamesRequest, _Response], _Response]:
    """The callback of a service that looks up each of the request's names into the list
    `field` of its response; one lookup failing with `errors` empties the list (what
    rclpy's parameter services answer for a name that is not there)."""

    def answer(request: _NamesRequest, response: _Response) -> _Response:
        try:
            found = [lookup(n) for n in request.names]
        except errors:
            found = []
        setattr(response, field, found)
        return response

    return answer


class ParameterService:
    """Creates the services on `node` (names relative to the node: `<node>/<service>`)."""

    def __init__(self, node: NodeInterface) -> None:
        from ros2lite.qos import qos_profile_parameters

        self._node = node
        callbacks: dict[str, Callable[..., object]] = {
            "describe_parameters": _all_or_none(
                "descriptors", node.describe_parameter, ParameterNotDeclaredException
            ),
            "get_parameters": _all_or_none(
                "values",
                lambda n: node.get_parameter(n).get_parameter_value(),
                (ParameterNotDeclaredException, ParameterUninitializedException),
            ),
            "get_parameter_types": _all_or_none(
                "types", lambda n: node.get_parameter_type(n).value, ParameterNotDeclaredException
            ),
            "list_parameters": self._list_parameters,
            "set_parameters": self._set_parameters,
            "set_parameters_atomically": self._set_parameters_atomically,
        }
        self.services: list[Service[Any, Any]] = [
            node.create_service(
                f"rcl_interfaces/srv/{type_name}",
                f"{node.get_name()}/{name}",
                callbacks[name],
                qos_profile=qos_profile_parameters,
            )
            for name, type_name in TYPES.items()
        ]

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
