"""What the `param` verbs share: their options, one body (connect, find the node, call its
parameter services through the library's client), completion and type names."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, TypeVar

import click

from .. import completion, numbers
from ..common import connect
from ..errors import CliError
from ..options import bind, strategy_options

if TYPE_CHECKING:
    from click.shell_completion import CompletionItem

    from ros2lite.task import Future
    from ros2lite.tools.connection import Connection

F = TypeVar("F", bound=Callable[..., Any])
T = TypeVar("T")

SERVICE_WAIT = 5.0  # how long ros2cli waits for a node's parameter services

# rcl_interfaces/msg/ParameterType number → how ros2cli names it
TYPE_NAMES = {
    0: "not set",
    1: "boolean",
    2: "integer",
    3: "double",
    4: "string",
    5: "byte array",
    6: "boolean array",
    7: "integer array",
    8: "double array",
    9: "string array",
}


@dataclass(frozen=True)
class Target:
    """The node a param verb talks to, and how: ros2cli's options shared by every verb."""

    node_name: str | None
    include_hidden_nodes: bool
    no_daemon: bool
    use_sim_time: bool
    timeout: float = 1.0
    service_timeout: float | None = None


def node_options(*, timeout: bool = True, node_required: bool = True) -> Callable[[F], F]:
    """node_name, --include-hidden-nodes, the strategy options and (but for list) --timeout
    and --service-timeout, handed to the verb as one `target: Target`."""

    def decorate(fn: F) -> F:
        cmd = bind(lambda: Target, 'target')(fn)
        if timeout:
            cmd = click.option(
                "--service-timeout",
                metavar="N",
                type=numbers.seconds(min_open=True),
                default=None,
                help="Maximum time to wait for service response in seconds "
                "(default: waits indefinitely)",
            )(cmd)
            cmd = click.option(
                "--timeout",
                metavar="N",
                type=numbers.Count(min=0, max=int(numbers.MAX_SECONDS)),
                default=1,
                show_default=True,
                help="Wait for N seconds until node becomes available",
            )(cmd)
        cmd = click.option(
            "--include-hidden-nodes", is_flag=True, help="Consider hidden nodes as well"
        )(cmd)
        cmd = click.argument("node_name", required=node_required, shell_complete=completion.nodes)(
            cmd
        )
        decorated: F = strategy_options()(cmd)
        return decorated

    return decorate


class Remote:
    """A verb's blocking view of one node's parameter services, through the library's one
    client; failures become ros2cli's lines."""

    def __init__(self, conn: Connection, fqn: str, service_timeout: float | None) -> None:
        from ros2lite.parameter_client import AsyncParameterClient

        self.conn = conn
        self.fqn = fqn
        self.service_timeout = service_timeout
        # a node that vanishes mid-call is reported at once, not after the timeout
        self.client = AsyncParameterClient(conn.node(), fqn, fail_without_server=True)

    def call(self, service: str, *args: object) -> Any:  # the response of `service`
        """Wait for `service`, call the client's method of that name with `args`, return the
        response."""
        if not self.client.wait_for_services(SERVICE_WAIT, [service]):
            raise CliError(
                f"Wait for service timed out waiting for parameter services for node {self.fqn}"
            )
        future: Future[object] = getattr(self.client, service)(*args)
        self.conn.spin_until_future_complete(future, self.service_timeout)
        if not future.done():
            why = f"service '{self.fqn}/{service}' did not answer within {self.service_timeout} s"
        elif future.exception() is not None:
            why = str(future.exception())
        else:
            return future.result()
        raise CliError(f"Exception while calling service of node '{self.fqn}': {why}")


def with_remote(target: Target, body: Callable[[Remote], T]) -> T:
    """What every single-node verb does: connect, find the node (else 'Node not found'),
    and run `body` against its parameter services."""
    from ros2lite.names import absolute_node_name

    assert target.node_name is not None
    fqn = absolute_node_name(target.node_name)
    with connect(no_daemon=target.no_daemon, use_sim_time=target.use_sim_time) as conn:
        if not conn.wait_for_node(
            fqn, include_hidden=target.include_hidden_nodes, timeout=target.timeout
        ):
            raise CliError("Node not found")
        return body(Remote(conn, fqn, target.service_timeout))


def complete_parameter_names(
    ctx: click.Context, _param: click.Parameter, incomplete: str
) -> list[CompletionItem]:
    """Names of the node's parameters, asked of the node itself; quick, quiet and without
    starting the daemon, like the other completers (nothing when anything fails)."""
    from click.shell_completion import CompletionItem

    try:
        names = _remote_parameter_names(ctx)
    except Exception:
        return []
    return [CompletionItem(n) for n in sorted(names) if n.startswith(incomplete)]


def complete_pair_names(
    ctx: click.Context, param: click.Parameter, incomplete: str
) -> list[CompletionItem]:
    """`param set`'s NAME VALUE...: the node's parameter names where a name goes (those not
    typed yet), nothing where a value does."""
    typed = ctx.params.get(param.name or "") or ()
    if len(typed) % 2:
        return []
    taken = set(typed[::2])
    return [
        item for item in complete_parameter_names(ctx, param, incomplete) if item.value not in taken
    ]


def _remote_parameter_names(ctx: click.Context) -> list[str]:
    from ros2lite.parameter_client import AsyncParameterClient
    from ros2lite.tools.connection import Connection

    node_name = ctx.params.get("node_name")
    if not node_name:
        return []
    router = ctx.find_root().params.get("router")
    with Connection(router=router, autostart=False) as conn:
        client = AsyncParameterClient(conn.node("_ros2lite_completion"), node_name)
        if not client.wait_for_services(1.0, ["list_parameters"]):
            return []
        future = client.list_parameters()
        conn.spin_until_future_complete(future, 1.0)
        response = future.result() if future.done() else None
        return list(response.result.names) if response is not None else []


def python_json(value: object) -> object:
    """A parameter's Python value in the JSON schema: floats as its floats (nan/inf as
    strings), a byte array as base64, lists as lists."""
    from ros2lite.interfaces.json_form import value_to_json

    if isinstance(value, dict):
        return {k: python_json(v) for k, v in value.items()}
    if isinstance(value, list) and value and all(isinstance(v, bytes) for v in value):
        return value_to_json(value)
    if isinstance(value, list):
        return [python_json(v) for v in value]
    return value_to_json(value)


def type_name(type_number: int) -> str:
    return TYPE_NAMES.get(type_number, f"unknown ({type_number})")
