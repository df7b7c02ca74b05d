"""Parameters of every node of the graph, named as the C++ bridge names them: `/node.param`.

A get or set asks each node concerned through its parameter services (all nodes at once,
each with a deadline); a node that once failed to answer is skipped afterwards, as the C++
bridge's `ignore_unresponsive_param_nodes` does.
"""

from __future__ import annotations

import base64
import re
import threading
import time
from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, Any

import foxglove

from ros2lite.parameter import Parameter
from ros2lite.parameter_client import AsyncParameterClient

if TYPE_CHECKING:
    from ros2lite.node import Node
    from ros2lite.task import Future

__all__ = ['RemoteParameters', 'split_name', 'to_foxglove', 'to_ros']

# rcl_interfaces/msg/ParameterType numbers
_DOUBLE, _BYTE_ARRAY, _DOUBLE_ARRAY = 3, 5, 8


def split_name(name: str) -> tuple[str, str] | None:
    """('/node', 'param') of '/node.param'; None for a name of no node (node names have no
    dots, parameter names may)."""
    node, dot, param = name.partition('.')
    if not dot or not node.startswith('/') or not param:
        return None
    return node, param


def to_foxglove(node: str, param: Parameter) -> foxglove.Parameter:
    """A ROS parameter of `node` as the protocol shows it (doubles and byte arrays typed, so
    a client can tell 1.0 from 1 and bytes from text)."""
    name = f'{node}.{param.name}'
    kind = param.type_.value
    value = param.value
    if kind == _DOUBLE:
        return foxglove.Parameter(name, value=float(value), type=foxglove.ParameterType.Float64)
    if kind == _DOUBLE_ARRAY:
        return foxglove.Parameter(
            name, value=[float(v) for v in value], type=foxglove.ParameterType.Float64Array
        )
    if kind == _BYTE_ARRAY:
        return foxglove.Parameter(name, value=b''.join(value))
    if value is None:
        return foxglove.Parameter(name)
    return foxglove.Parameter(name, value=list(value) if kind > _BYTE_ARRAY else value)


def to_ros(param: foxglove.Parameter, name: str, current: Parameter | None) -> Parameter:
    """The ROS parameter a client's value stands for; a whole number given for a double
    parameter stays a double (JSON cannot tell 2 from 2.0)."""
    value: Any = param.get_value()
    hint = param.type
    if hint == foxglove.ParameterType.ByteArray and isinstance(value, str):
        value = base64.b64decode(value)
    if isinstance(value, bytes):
        return Parameter(name, Parameter.Type.BYTE_ARRAY, [bytes([b]) for b in value])
    wants_double = hint in (foxglove.ParameterType.Float64, foxglove.ParameterType.Float64Array)
    if current is not None and current.type_.value in (_DOUBLE, _DOUBLE_ARRAY):
        wants_double = True
    if wants_double and isinstance(value, int) and not isinstance(value, bool):
        value = float(value)
    elif wants_double and isinstance(value, list):
        value = [float(v) if isinstance(v, int) and not isinstance(v, bool) else v for v in value]
    if isinstance(value, dict):
        raise ValueError(f"parameter '{name}': ROS parameters hold no maps")
    return Parameter(name, value=value)


class RemoteParameters:
    """Reads and writes the parameters of the graph's nodes for the bridge."""

    def __init__(
        self,
        node: Node,
        nodes: Callable[[], list[str]],
        whitelist: Sequence[re.Pattern[str]],
        *,
        timeout: float = 2.0,
        ignore_unresponsive: bool = True,
        warn: Callable[[str], object] = print,
    ) -> None:
        self._node = node
        self._nodes = nodes  # fully qualified names of the graph's nodes now
        self._whitelist = whitelist
        self._timeout = timeout
        self._ignore_unresponsive = ignore_unresponsive
        self._warn = warn
        self._clients: dict[str, AsyncParameterClient] = {}
        self._unresponsive: set[str] = set()
        self._lock = threading.Lock()

    def allowed(self, name: str) -> bool:
        """Whether `/node.param` passes the param_whitelist."""
        return any(p.fullmatch(name) for p in self._whitelist)

    def _client(self, node: str) -> AsyncParameterClient:
        with self._lock:
            client = self._clients.get(node)
            if client is None:
                client = self._clients[node] = AsyncParameterClient(
                    self._node, node, fail_without_server=True
                )
            return client

    def _wait(self, futures: dict[str, Future[Any]]) -> dict[str, Any]:
        """The results of futures (node -> future) that complete in time; a node that does
        not answer is remembered as unresponsive."""
        deadline = time.monotonic() + self._timeout
        results: dict[str, Any] = {}
        for node, future in futures.items():
            done = threading.Event()
            future.add_done_callback(_setter(done))
            if not done.wait(max(0.0, deadline - time.monotonic())) or future.exception():
                if self._ignore_unresponsive:
                    self._unresponsive.add(node)
                self._warn(f"Failed to retrieve parameters from node '{node}'")
                continue
            results[node] = future.result()
        return results

    def get(self, names: Iterable[str]) -> list[foxglove.Parameter]:
        """The values of `/node.param` names; every whitelisted parameter of every node when
        `names` is empty."""
        wanted: dict[str, list[str]] = {}
        for name in names:
            split = split_name(name)
            if split is not None and self.allowed(name):
                wanted.setdefault(split[0], []).append(split[1])
        if not wanted and not names:
            listed = self._wait(
                {
                    n: self._client(n).list_parameters()
                    for n in self._nodes()
                    if n not in self._unresponsive
                }
            )
            wanted = {node: list(reply.result.names) for node, reply in listed.items()}
        out: list[foxglove.Parameter] = []
        replies = self._wait({n: self._client(n).get_parameters(ps) for n, ps in wanted.items()})
        for node, reply in replies.items():
            for pname, value in zip(wanted[node], reply.values, strict=False):
                if not self.allowed(f'{node}.{pname}'):
                    continue
                param = Parameter.from_parameter_msg(_message(pname, value))
                out.append(to_foxglove(node, param))
        return out

    def set(self, params: Iterable[foxglove.Parameter]) -> list[foxglove.Parameter]:
        """Set parameters by `/node.param` name; returns their values afterwards."""
        by_node: dict[str, list[foxglove.Parameter]] = {}
        for p in params:
            split = split_name(p.name)
            if split is None or not self.allowed(p.name):
                self._warn(f"Parameter '{p.name}' is not a whitelisted /node.param name")
                continue
            by_node.setdefault(split[0], []).append(p)
        current = {
            f'{p.name}': p for p in self.get([q.name for ps in by_node.values() for q in ps])
        }
        futures: dict[str, Future[Any]] = {}
        sent: dict[str, list[Parameter]] = {}
        for node, ps in by_node.items():
            ros_params = []
            for p in ps:
                pname = split_name(p.name)[1]  # type: ignore[index]  # checked above
                known = current.get(p.name)
                before = None if known is None else to_ros(known, pname, None)
                try:
                    ros_params.append(to_ros(p, pname, before))
                except (TypeError, ValueError) as e:
                    self._warn(f"Cannot set '{p.name}': {e}")
            if ros_params:
                futures[node] = self._client(node).set_parameters(ros_params)
                sent[node] = ros_params
        for node, reply in self._wait(futures).items():
            # one result per parameter sent, in order (rcl_interfaces/srv/SetParameters)
            for q, result in zip(sent[node], reply.results, strict=False):
                if not result.successful:
                    self._warn(f"Failed to set '{node}.{q.name}': {result.reason}")
        return self.get([p.name for ps in by_node.values() for p in ps])


def _setter(event: threading.Event) -> Callable[[object], None]:
    def done(_future: object) -> None:
        event.set()

    return done


def _message(name: str, value: Any) -> Any:
    from ros2lite.interfaces import get_interface

    return get_interface('rcl_interfaces/msg/Parameter')(name=name, value=value)
