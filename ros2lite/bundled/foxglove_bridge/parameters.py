"""Parameters of every node of the graph, named as the C++ bridge names them: `/node.param`.

A get or set asks each node concerned through its parameter services (all nodes at once,
each with a deadline, on a thread of ours); a node that once failed to answer is skipped
afterwards, as the C++ bridge's `ignore_unresponsive_param_nodes` does.
"""

from __future__ import annotations

import base64
import queue
import re
import threading
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
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


@dataclass
class _Job:
    """Work for the parameter thread: a get (node -> names, None for all of them) or a set
    (node -> parameters); `done` is set when every node answered or the deadline passed."""

    kind: str  # 'get' or 'set'
    nodes: dict[str, Any]
    done: threading.Event = field(default_factory=threading.Event)


_WAKE = _Job('wake', {})  # nothing to do but look at the jobs under way


class RemoteParameters:
    """Reads and writes the parameters of the graph's nodes for the bridge.

    The SDK serves no client while one of its listener calls runs (a slow `getParameters`
    holds every other client's handshake), so a request never waits long: the asking happens
    on a thread of ours, the answer comes from what is known after at most `answer_within`
    seconds, and only nodes of the graph are asked (a name of a node that does not exist
    costs a set lookup, not a client). Values are kept per node, refreshed by each request
    and by `/parameter_events`, and dropped with the node when it leaves the graph."""

    def __init__(
        self,
        node: Node,
        nodes: Callable[[], list[str]],
        whitelist: Sequence[re.Pattern[str]],
        *,
        timeout: float = 2.0,
        answer_within: float = 0.5,
        ignore_unresponsive: bool = True,
        warn: Callable[[str], object] = print,
    ) -> None:
        self._node = node
        self._nodes = nodes  # fully qualified names of the graph's nodes now
        self._whitelist = whitelist
        self._timeout = timeout
        self._answer_within = answer_within
        self._ignore_unresponsive = ignore_unresponsive
        self._warn = warn
        self._clients: dict[str, AsyncParameterClient] = {}  # the parameter thread's only
        self._values: dict[str, dict[str, foxglove.Parameter]] = {}
        self._unresponsive: set[str] = set()
        self._in_flight: dict[str, int] = {}  # node -> jobs asking it now
        self._watched: set[str] = set()
        self._lock = threading.Lock()
        self._jobs: queue.Queue[_Job | None] = queue.Queue()
        self._thread: threading.Thread | None = None

    def start(self) -> None:
        """Start the thread that asks the nodes."""
        self._thread = threading.Thread(
            target=self._work, name='foxglove-bridge-parameters', daemon=True
        )
        self._thread.start()

    def close(self) -> None:
        """Stop asking; the clients made are destroyed."""
        if self._thread is not None:
            self._jobs.put(None)
            self._thread.join(self._timeout + 3.0)
            self._thread = None

    def allowed(self, name: str) -> bool:
        """Whether `/node.param` passes the param_whitelist."""
        return any(p.fullmatch(name) for p in self._whitelist)

    # -- the SDK's threads ---------------------------------------------------------------------
    def get(self, names: Iterable[str]) -> list[foxglove.Parameter]:
        """The values of `/node.param` names; every whitelisted parameter of every node when
        `names` is empty. Names of nodes not in the graph are answered with nothing."""
        names = list(names)
        graph = set(self._nodes())
        wanted: dict[str, list[str] | None] = {}
        if not names:
            wanted = dict.fromkeys(sorted(graph - self._unresponsive))
        for name in names:
            split = split_name(name)
            if split is None or split[0] not in graph or not self.allowed(name):
                continue
            if split[0] in self._unresponsive:
                continue
            asked = wanted.setdefault(split[0], [])
            if asked is not None and split[1] not in asked:
                asked.append(split[1])
        self._ask(_Job('get', dict(wanted)))
        return self._known(wanted)

    def set(self, params: Iterable[foxglove.Parameter]) -> list[foxglove.Parameter]:
        """Set parameters by `/node.param` name; returns their values as known afterwards."""
        graph = set(self._nodes())
        by_node: dict[str, list[Parameter]] = {}
        asked: dict[str, list[str] | None] = {}
        for p in params:
            split = split_name(p.name)
            if split is None or not self.allowed(p.name):
                self._warn(f"Parameter '{p.name}' is not a whitelisted /node.param name")
                continue
            node, pname = split
            if node not in graph:
                self._warn(f"Cannot set '{p.name}': no node '{node}' in the graph")
                continue
            with self._lock:
                known = self._values.get(node, {}).get(pname)
            before = None if known is None else to_ros(known, pname, None)
            try:
                by_node.setdefault(node, []).append(to_ros(p, pname, before))
            except (TypeError, ValueError) as e:
                self._warn(f"Cannot set '{p.name}': {e}")
                continue
            names = asked.setdefault(node, [])
            assert names is not None
            names.append(pname)
        self._ask(_Job('set', dict(by_node)))
        return self._known(asked)

    def watch(self, names: Iterable[str]) -> None:
        """Clients now watch these parameters (their changes are published)."""
        with self._lock:
            self._watched.update(n for n in names if split_name(n) is not None)

    def unwatch(self, names: Iterable[str]) -> None:
        """No client watches these parameters any more."""
        with self._lock:
            self._watched.difference_update(names)

    # -- the executor's thread -----------------------------------------------------------------
    def on_event(self, event: Any) -> list[foxglove.Parameter]:
        """A `/parameter_events` message: what is known follows it; the watched parameters
        among its changes are returned (for the clients)."""
        node = event.node
        changed = []
        with self._lock:
            values = self._values.get(node)
            watched = set(self._watched)
        for p in [*event.new_parameters, *event.changed_parameters]:
            name = f'{node}.{p.name}'
            if not self.allowed(name):
                continue
            value = to_foxglove(node, Parameter.from_parameter_msg(p))
            if values is not None:
                with self._lock:
                    values[p.name] = value
            if name in watched:
                changed.append(value)
        if values is not None:
            with self._lock:
                for p in event.deleted_parameters:
                    values.pop(p.name, None)
        return changed

    # -- asking --------------------------------------------------------------------------------
    def _ask(self, job: _Job) -> None:
        """Queue the job; wait for it a short while, unless one of its nodes is still being
        asked (then a get leaves that node out and nothing waits: a flood waits once)."""
        with self._lock:
            busy = [n for n in job.nodes if self._in_flight.get(n)]
            if job.kind == 'get':
                job.nodes = {n: v for n, v in job.nodes.items() if n not in busy}
            for n in job.nodes:
                self._in_flight[n] = self._in_flight.get(n, 0) + 1
        if not job.nodes:
            return
        self._jobs.put(job)
        if not busy:
            job.done.wait(self._answer_within)

    def _known(self, wanted: dict[str, list[str] | None]) -> list[foxglove.Parameter]:
        out: list[foxglove.Parameter] = []
        with self._lock:
            for node, names in wanted.items():
                values = self._values.get(node, {})
                if names is None:
                    out += [values[n] for n in sorted(values)]
                else:
                    out += [values[n] for n in names if n in values]
        return out

    def _work(self) -> None:
        """Make clients and send requests; never wait on a reply (callbacks keep the
        answers), so one silent node holds up no other request."""
        pending: list[tuple[float, _Job, dict[str, threading.Event]]] = []
        while True:
            try:
                job = self._jobs.get(timeout=0.1 if pending else None)
            except queue.Empty:
                job = _WAKE
            if job is None:
                break
            if job.nodes:
                answered: dict[str, threading.Event] = {}
                try:
                    self._reap()
                    for node, what in job.nodes.items():
                        answered[node] = done = threading.Event()
                        if job.kind == 'get':
                            self._fetch(node, what, done)
                        else:
                            self._set(node, what, done)
                except Exception as e:  # a bad node must not end the parameter thread
                    self._warn(f'foxglove_bridge: parameters: {e}')
                for node in job.nodes:
                    if node not in answered:
                        self._release(node)
                pending.append((time.monotonic() + self._timeout, job, answered))
            pending = [p for p in pending if not self._settled(*p)]
        for client in self._clients.values():
            client.destroy()
        self._clients.clear()

    def _settled(self, deadline: float, job: _Job, answered: dict[str, threading.Event]) -> bool:
        """Whether a job is over; each node is no longer being asked once it answered or its
        deadline passed (a silent one is then unresponsive)."""
        late = time.monotonic() > deadline
        for node in [n for n, done in answered.items() if done.is_set() or late]:
            if not answered.pop(node).is_set():
                self._failed(node)
            self._release(node)
        if answered:
            return False
        job.done.set()
        return True

    def _release(self, node: str) -> None:
        with self._lock:
            left = self._in_flight.get(node, 0) - 1
            if left > 0:
                self._in_flight[node] = left
            else:
                self._in_flight.pop(node, None)

    def _reap(self) -> None:
        """Clients and values of nodes that left the graph go."""
        graph = set(self._nodes())
        for node in [n for n in self._clients if n not in graph]:
            self._clients.pop(node).destroy()
        with self._lock:
            for node in [n for n in self._values if n not in graph]:
                del self._values[node]
            self._unresponsive &= graph

    def _client(self, node: str) -> AsyncParameterClient:
        client = self._clients.get(node)
        if client is None:
            client = self._clients[node] = AsyncParameterClient(
                self._node, node, fail_without_server=True
            )
        return client

    def _fetch(self, node: str, names: list[str] | None, done: threading.Event) -> None:
        """Ask `node` for `names` (a list of all of them first when None)."""
        client = self._client(node)
        if names is not None:
            self._get(node, client, names, False, done)
            return

        def listed(future: Future[Any]) -> None:
            reply = future.result() if future.exception() is None else None
            if reply is not None:
                self._get(node, client, list(reply.result.names), True, done)

        client.list_parameters().add_done_callback(listed)

    def _get(
        self,
        node: str,
        client: AsyncParameterClient,
        names: list[str],
        every: bool,
        done: threading.Event,
    ) -> None:
        def store(future: Future[Any]) -> None:
            reply = future.result() if future.exception() is None else None
            if reply is not None:
                self._store(node, names, reply.values, every)
                done.set()
                self._jobs.put(_WAKE)  # the job may be over: the worker looks

        client.get_parameters(names).add_done_callback(store)

    def _store(self, node: str, names: list[str], values: Any, every: bool) -> None:
        found = {}
        for pname, value in zip(names, values, strict=False):
            if self.allowed(f'{node}.{pname}'):
                param = Parameter.from_parameter_msg(_message(pname, value))
                found[pname] = to_foxglove(node, param)
        with self._lock:
            if every:
                self._values[node] = found
            else:
                self._values.setdefault(node, {}).update(found)

    def _set(self, node: str, params: list[Parameter], done: threading.Event) -> None:
        """Set `params` on `node`, then read them back."""
        client = self._client(node)

        def was_set(future: Future[Any]) -> None:
            reply = future.result() if future.exception() is None else None
            if reply is None:
                return
            # one result per parameter sent, in order (rcl_interfaces/srv/SetParameters)
            for q, result in zip(params, reply.results, strict=False):
                if not result.successful:
                    self._warn(f"Failed to set '{node}.{q.name}': {result.reason}")
            self._get(node, client, [p.name for p in params], False, done)

        client.set_parameters(params).add_done_callback(was_set)

    def _failed(self, node: str) -> None:
        if self._ignore_unresponsive:
            with self._lock:
                self._unresponsive.add(node)
        self._warn(f"Failed to retrieve parameters from node '{node}'")


def _message(name: str, value: Any) -> Any:
    from ros2lite.interfaces import get_interface

    return get_interface('rcl_interfaces/msg/Parameter')(name=name, value=value)
