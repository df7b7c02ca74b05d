"""rclpy's `AsyncParameterClient`: another node's six parameter services, as futures.

The one client of remote parameters: scripts, `launch` and the `param` verbs all use it.
Each call returns the Future of the service response; it completes on the executor of
`node` (e.g. `ros2lite.spin_until_future_complete(node, future)`), and `callback`, if given,
is added as its done-callback. Clients are created on first use, so a caller that needs one
service (a CLI verb) declares only that one.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

from ros2lite.names import absolute_node_name
from ros2lite.parameter import Parameter
from ros2lite.parameters.services import SERVICES, TYPES
from ros2lite.qos import QoSProfile, qos_profile_services_default
from ros2lite.task import Future

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.client import Client
    from ros2lite.interfaces import Message, ServiceType
    from ros2lite.msgs.rcl_interfaces import srv
    from ros2lite.msgs.rcl_interfaces.msg import Parameter as ParameterMsg
    from ros2lite.node import Node

__all__ = ['AsyncParameterClient']

_ResponseT = TypeVar('_ResponseT')
DoneCallback = Callable[[Future[_ResponseT]], object]
"""Called with the future of a call once it is done."""


def service_type(service: str) -> type[ServiceType]:
    """The rcl_interfaces service class of one of the six parameter services."""
    from ros2lite.interfaces import get_interface

    found: type[ServiceType] = get_interface(f'rcl_interfaces/srv/{TYPES[service]}')
    return found


class AsyncParameterClient:
    """Clients of `remote_node_name`'s parameter services, created on `node` when used."""

    def __init__(
        self,
        node: Node,
        remote_node_name: str,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: CallbackGroup | None = None,
    ) -> None:
        self._node = node
        self.remote_node_name = absolute_node_name(remote_node_name)
        self._qos = qos_profile
        self._group = callback_group
        self._clients: dict[str, Client[Message, Message]] = {}

    def _client(self, service: str) -> Client[Message, Message]:
        client = self._clients.get(service)
        if client is None:
            client = self._clients[service] = self._node.create_client(
                service_type(service),
                f'{self.remote_node_name}/{service}',
                qos_profile=self._qos,
                callback_group=self._group,
            )
        return client

    def services_are_ready(self, services: Sequence[str] = SERVICES) -> bool:
        """Whether a server of each of the (given) services is in the graph now."""
        return all(self._client(s).service_is_ready() for s in services)

    def wait_for_services(
        self, timeout_sec: float | None = None, services: Sequence[str] = SERVICES
    ) -> bool:
        """Wait until the (given) services are available; False if `timeout_sec` passed."""
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        for service in services:
            left = None if deadline is None else max(0.0, deadline - time.monotonic())
            if not self._client(service).wait_for_service(timeout_sec=left):
                return False
        return True

    def _call(
        self, service: str, callback: DoneCallback[Any] | None, **fields: object
    ) -> Future[Any]:
        """Call `service` with a request of `fields` (the caller knows the response type)."""
        future = self._client(service).call_async(service_type(service).Request(**fields))
        if callback is not None:
            future.add_done_callback(callback)
        return future

    def list_parameters(
        self,
        prefixes: Sequence[str] | None = None,
        depth: int | None = None,
        callback: DoneCallback[srv.ListParameters.Response] | None = None,
    ) -> Future[srv.ListParameters.Response]:
        """Names (and prefixes) of the node's parameters, optionally under `prefixes`."""
        return self._call(
            'list_parameters',
            callback,
            prefixes=list(prefixes or []),
            depth=depth or 0,
        )

    def get_parameters(
        self,
        names: Sequence[str],
        callback: DoneCallback[srv.GetParameters.Response] | None = None,
    ) -> Future[srv.GetParameters.Response]:
        """The values of `names` (an empty reply when any of them is unknown)."""
        return self._call('get_parameters', callback, names=list(names))

    def get_parameter_types(
        self,
        names: Sequence[str],
        callback: DoneCallback[srv.GetParameterTypes.Response] | None = None,
    ) -> Future[srv.GetParameterTypes.Response]:
        """The ParameterType numbers of `names`."""
        return self._call('get_parameter_types', callback, names=list(names))

    def describe_parameters(
        self,
        names: Sequence[str],
        callback: DoneCallback[srv.DescribeParameters.Response] | None = None,
    ) -> Future[srv.DescribeParameters.Response]:
        """The descriptors of `names` (an empty reply when any of them is unknown)."""
        return self._call('describe_parameters', callback, names=list(names))

    def set_parameters(
        self,
        parameters: Sequence[Parameter | ParameterMsg],
        callback: DoneCallback[srv.SetParameters.Response] | None = None,
    ) -> Future[srv.SetParameters.Response]:
        """Set each of `parameters` (Parameters or rcl_interfaces/msg/Parameter messages);
        one result per parameter."""
        return self._call(
            'set_parameters',
            callback,
            parameters=parameter_messages(parameters),
        )

    def set_parameters_atomically(
        self,
        parameters: Sequence[Parameter | ParameterMsg],
        callback: DoneCallback[srv.SetParametersAtomically.Response] | None = None,
    ) -> Future[srv.SetParametersAtomically.Response]:
        """Set all of `parameters` or none; one result for all."""
        return self._call(
            'set_parameters_atomically',
            callback,
            parameters=parameter_messages(parameters),
        )

    def delete_parameters(
        self,
        names: Sequence[str],
        callback: DoneCallback[srv.SetParameters.Response] | None = None,
    ) -> Future[srv.SetParameters.Response]:
        """Set each to NOT_SET, which undeclares it where the node allows that."""
        return self.set_parameters([Parameter(n) for n in names], callback)

    def load_parameter_file(
        self,
        parameter_file: str | Path,
        use_wildcard: bool = False,
        callback: DoneCallback[srv.SetParameters.Response] | None = None,
    ) -> Future[srv.SetParameters.Response]:
        """Set the file's parameters for the remote node (its entries, and `/**`-style ones
        when `use_wildcard`), one by one."""
        return self.set_parameters(self.file_parameters(parameter_file, use_wildcard), callback)

    def load_parameter_file_atomically(
        self,
        parameter_file: str | Path,
        use_wildcard: bool = False,
        callback: DoneCallback[srv.SetParametersAtomically.Response] | None = None,
    ) -> Future[srv.SetParametersAtomically.Response]:
        """Like :meth:`load_parameter_file`, all or nothing."""
        return self.set_parameters_atomically(
            self.file_parameters(parameter_file, use_wildcard), callback
        )

    def file_parameters(self, parameter_file: str | Path, use_wildcard: bool) -> list[Parameter]:
        """The Parameters a parameters file gives the remote node, checked on the way."""
        from ros2lite.parameters.files import parameters_for_node

        return parameters_for_node(parameter_file, self.remote_node_name, use_wildcard)

    def destroy(self) -> None:
        """Destroy the clients made so far."""
        for client in self._clients.values():
            self._node.destroy_client(client)
        self._clients.clear()


def parameter_messages(parameters: Sequence[Parameter | ParameterMsg]) -> list[ParameterMsg]:
    """rcl_interfaces/msg/Parameter messages from Parameters (messages pass through)."""
    return [p.to_parameter_msg() if isinstance(p, Parameter) else p for p in parameters]
