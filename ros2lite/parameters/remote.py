"""Another node's parameters, through its six parameter services (blocking calls).

This is what `ros2lite param` verbs are made of, and what scripts or `launch` use to read,
set, dump or load a running node's parameters:

    remote = RemoteParameters(my_node, '/turtlesim')
    remote.wait_for_services(5.0) or fail()
    values = remote.get_parameters(['background_r'])
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

from ros2lite.exceptions import Ros2liteError
from ros2lite.parameter import Parameter, parameter_value_to_python
from ros2lite.parameters.files import dump_yaml, values_for_node
from ros2lite.parameters.services import SERVICES, TYPES

SERVICE_WAIT = 5.0  # how long ros2cli waits for a node's parameter services


class ParameterServiceError(Ros2liteError, RuntimeError):
    """A parameter service did not answer; the message is the one ros2cli prints."""


def absolute_node_name(name: str) -> str:
    return name if name.startswith("/") else "/" + name


def is_hidden_node(fqn: str) -> bool:
    return any(part.startswith("_") for part in fqn.split("/") if part)


def wait_for_node(
    node_names: Callable[[], Iterable[str]], fqn: str, include_hidden: bool, timeout: float
) -> bool:
    """Poll `node_names()` until `fqn` is among them (hidden ones only if asked)."""
    if is_hidden_node(fqn) and not include_hidden:
        return False
    deadline = time.monotonic() + max(0.0, timeout)
    while True:
        if fqn in set(node_names()):
            return True
        if time.monotonic() >= deadline:
            return False
        time.sleep(0.05)


def _srv(name: str) -> Any:
    from ros2lite.interfaces import get_interface

    return get_interface(f"rcl_interfaces/srv/{TYPES[name]}")


def _as_msg(param: Any) -> Any:
    return param.to_parameter_msg() if isinstance(param, Parameter) else param


class RemoteParameters:
    """Blocking client of `fqn`'s parameter services, made from `node` (clients on demand)."""

    def __init__(self, node: Any, fqn: str, *, service_timeout: float | None = None) -> None:
        self.node = node
        self.fqn = absolute_node_name(fqn)
        self.service_timeout = service_timeout
        self._clients: dict[str, Any] = {}

    def _client(self, service: str) -> Any:
        client = self._clients.get(service)
        if client is None:
            client = self.node.create_client(_srv(service), f"{self.fqn}/{service}")
            self._clients[service] = client
        return client

    def wait_for_services(
        self, timeout_sec: float | None = SERVICE_WAIT, services: Sequence[str] = SERVICES
    ) -> bool:
        """Whether all the given parameter services became available in time."""
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        for service in services:
            left = None if deadline is None else max(0.0, deadline - time.monotonic())
            if not self._client(service).wait_for_service(timeout_sec=left):
                return False
        return True

    def _call(self, service: str, **fields: Any) -> Any:
        if not self.wait_for_services(SERVICE_WAIT, [service]):
            raise ParameterServiceError(
                f"Wait for service timed out waiting for parameter services for node {self.fqn}"
            )
        from ros2lite.client import ServiceCallError

        request = _srv(service).Request(**fields)
        try:
            return self._client(service).call(request, timeout_sec=self.service_timeout)
        except (TimeoutError, ServiceCallError) as e:
            raise ParameterServiceError(
                f"Exception while calling service of node '{self.fqn}': {e}"
            ) from None

    # -- the six services ------------------------------------------------------------------
    def list_parameters(self, prefixes: Sequence[str] = (), depth: int = 0) -> Any:
        """A ListParametersResult (names and prefixes)."""
        return self._call("list_parameters", prefixes=list(prefixes), depth=depth).result

    def get_parameters(self, names: Sequence[str]) -> list[Any]:
        """ParameterValues; empty when any name is unknown to the node (as rclpy answers)."""
        return list(self._call("get_parameters", names=list(names)).values)

    def get_parameter_types(self, names: Sequence[str]) -> list[int]:
        return list(self._call("get_parameter_types", names=list(names)).types)

    def describe_parameters(self, names: Sequence[str]) -> list[Any]:
        return list(self._call("describe_parameters", names=list(names)).descriptors)

    def set_parameters(self, parameters: Sequence[Any]) -> list[Any]:
        """One SetParametersResult per parameter (Parameters or rcl_interfaces messages)."""
        return list(
            self._call("set_parameters", parameters=[_as_msg(p) for p in parameters]).results
        )

    def set_parameters_atomically(self, parameters: Sequence[Any]) -> Any:
        return self._call(
            "set_parameters_atomically", parameters=[_as_msg(p) for p in parameters]
        ).result

    # -- built on them -----------------------------------------------------------------------
    def delete_parameters(self, names: Sequence[str]) -> list[Any]:
        """Setting a parameter to NOT_SET undeclares it (if its descriptor allows)."""
        return self.set_parameters([Parameter(n) for n in names])

    def get_values(self) -> dict[str, Any]:
        """Every parameter's Python value, by name."""
        names = sorted(self.list_parameters().names)
        values = self.get_parameters(names) if names else []
        return {n: parameter_value_to_python(v) for n, v in zip(names, values, strict=False)}

    def dump_yaml(self) -> str:
        """The node's parameters as a parameters file (what `param dump` prints)."""
        return dump_yaml(self.fqn, self.get_values())

    def load_parameter_file(
        self, path: str | Path, use_wildcard: bool = True
    ) -> list[tuple[str, Any]]:
        """Set the file's parameters for this node one by one; (name, result) for each.

        Values keep the types the YAML file gives them (so a dump loads back unchanged).
        """
        from ros2lite.parameters.files import ParamsFileError, read_params_file

        values = values_for_node(path, self.fqn, use_wildcard=use_wildcard)
        if not values:
            nodes = [name for name, _ in read_params_file(path)]
            raise ParamsFileError(
                f"Param file does not contain parameters for {self.fqn}, only for nodes: {nodes}"
            )
        params = []
        for name, value in values.items():
            try:
                params.append(Parameter(name, value=value))
            except (TypeError, ValueError) as e:
                raise ParamsFileError(f"Parameter '{name}' in '{path}': {e}") from None
        return list(zip([p.name for p in params], self.set_parameters(params), strict=False))
