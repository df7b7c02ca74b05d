"""rclpy's `AsyncParameterClient`: another node's parameter services, as futures.

Each call returns the Future of the service response (complete it by spinning the node, e.g.
`ros2lite.spin_until_future_complete(node, future)`); `callback`, if given, is added as its
done-callback. For blocking calls from a script or a CLI, see `ros2lite.parameters.remote`.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from typing import Any

from ros2lite.parameter import Parameter
from ros2lite.parameters.services import SERVICES, TYPES
from ros2lite.qos import QoSProfile, qos_profile_services_default

DoneCallback = Callable[[Any], None]


class AsyncParameterClient:
    """Clients of `remote_node_name`'s six parameter services, created on `node`."""

    def __init__(
        self,
        node: Any,
        remote_node_name: str,
        qos_profile: QoSProfile = qos_profile_services_default,
        callback_group: Any = None,
    ) -> None:
        from ros2lite.interfaces import get_interface

        self._node = node
        self._remote_node_name = remote_node_name
        self._types = {s: get_interface(f"rcl_interfaces/srv/{TYPES[s]}") for s in SERVICES}
        self._clients = {
            s: node.create_client(
                self._types[s],
                f"{remote_node_name}/{s}",
                qos_profile=qos_profile,
                callback_group=callback_group,
            )
            for s in SERVICES
        }

    def services_are_ready(self) -> bool:
        return all(c.service_is_ready() for c in self._clients.values())

    def wait_for_services(self, timeout_sec: float | None = None) -> bool:
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        for client in self._clients.values():
            left = None if deadline is None else max(0.0, deadline - time.monotonic())
            if not client.wait_for_service(timeout_sec=left):
                return False
        return True

    def _call(self, service: str, callback: DoneCallback | None, **fields: Any) -> Any:
        future = self._clients[service].call_async(self._types[service].Request(**fields))
        if callback is not None:
            future.add_done_callback(callback)
        return future

    def list_parameters(
        self,
        prefixes: Sequence[str] | None = None,
        depth: int | None = None,
        callback: DoneCallback | None = None,
    ) -> Any:
        return self._call(
            "list_parameters", callback, prefixes=list(prefixes or []), depth=depth or 0
        )

    def get_parameters(self, names: Sequence[str], callback: DoneCallback | None = None) -> Any:
        return self._call("get_parameters", callback, names=list(names))

    def get_parameter_types(
        self, names: Sequence[str], callback: DoneCallback | None = None
    ) -> Any:
        return self._call("get_parameter_types", callback, names=list(names))

    def describe_parameters(
        self, names: Sequence[str], callback: DoneCallback | None = None
    ) -> Any:
        return self._call("describe_parameters", callback, names=list(names))

    def set_parameters(
        self, parameters: Sequence[Any], callback: DoneCallback | None = None
    ) -> Any:
        """`parameters`: Parameters or rcl_interfaces/msg/Parameter messages."""
        return self._call("set_parameters", callback, parameters=_messages(parameters))

    def set_parameters_atomically(
        self, parameters: Sequence[Any], callback: DoneCallback | None = None
    ) -> Any:
        return self._call("set_parameters_atomically", callback, parameters=_messages(parameters))

    def delete_parameters(self, names: Sequence[str], callback: DoneCallback | None = None) -> Any:
        """Set each to NOT_SET, which undeclares it where the node allows that."""
        return self.set_parameters([Parameter(n) for n in names], callback)

    def load_parameter_file(
        self, parameter_file: str, use_wildcard: bool = False, callback: DoneCallback | None = None
    ) -> Any:
        """Set the file's parameters for the remote node (its entries, and `/**`-style ones
        when `use_wildcard`), one by one."""
        return self.set_parameters(self._file_parameters(parameter_file, use_wildcard), callback)

    def load_parameter_file_atomically(
        self, parameter_file: str, use_wildcard: bool = False, callback: DoneCallback | None = None
    ) -> Any:
        return self.set_parameters_atomically(
            self._file_parameters(parameter_file, use_wildcard), callback
        )

    def _file_parameters(self, parameter_file: str, use_wildcard: bool) -> list[Parameter]:
        from ros2lite.parameters.files import values_for_node
        from ros2lite.parameters.remote import absolute_node_name

        fqn = absolute_node_name(self._remote_node_name)
        values = values_for_node(parameter_file, fqn, use_wildcard=use_wildcard)
        return [Parameter(n, value=v) for n, v in values.items()]

    def destroy(self) -> None:
        for client in self._clients.values():
            self._node.destroy_client(client)
        self._clients.clear()


def _messages(parameters: Sequence[Any]) -> list[Any]:
    return [p.to_parameter_msg() if isinstance(p, Parameter) else p for p in parameters]
