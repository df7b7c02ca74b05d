"""What the `param` verbs share: their options, finding the node, and type names."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

import click

from .. import completion
from ..common import CliSession, strategy_options
from ..errors import CliError

F = TypeVar("F", bound=Callable[..., Any])

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


def node_options(*, timeout: bool = True, node_required: bool = True) -> Callable[[F], F]:
    """node_name, --include-hidden-nodes, the strategy options and (but for list) --timeout."""

    def decorate(fn: F) -> F:
        if timeout:
            fn = click.option(
                "--service-timeout",
                metavar="N",
                type=float,
                default=None,
                help="Maximum time to wait for service response in seconds "
                "(default: waits indefinitely)",
            )(fn)
            fn = click.option(
                "--timeout",
                metavar="N",
                type=int,
                default=1,
                show_default=True,
                help="Wait for N seconds until node becomes available",
            )(fn)
        fn = click.option(
            "--include-hidden-nodes", is_flag=True, help="Consider hidden nodes as well"
        )(fn)
        fn = click.argument("node_name", required=node_required, shell_complete=completion.nodes)(
            fn
        )
        return strategy_options()(fn)

    return decorate


class GreedyOption(click.Option):
    """An option that takes every following word up to the next option, like argparse's
    `nargs='+'` (`--param-prefixes a b`); repeating the option adds more."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.update(multiple=True, type=click.UNPROCESSED)
        super().__init__(*args, **kwargs)

    def add_to_parser(self, parser: Any, ctx: click.Context) -> None:
        super().add_to_parser(parser, ctx)
        for name in self.opts:
            option = parser._long_opt.get(name) or parser._short_opt.get(name)
            if option is None:
                continue
            original = option.process

            def process(value: Any, state: Any, original: Any = original) -> None:
                words = [value]
                while state.rargs and not state.rargs[0].startswith("-"):
                    words.append(state.rargs.pop(0))
                original(tuple(words), state)

            option.process = process

    def type_cast_value(self, ctx: click.Context, value: Any) -> Any:
        # (('a', 'b'), ('c',)) from two uses → ('a', 'b', 'c')
        return tuple(
            w for group in value or () for w in (group if isinstance(group, tuple) else (group,))
        )


def connect(
    session: CliSession,
    node_name: str,
    include_hidden_nodes: bool,
    timeout: float,
    service_timeout: float | None,
) -> Any:
    """The remote node's parameters, once the node is in the graph (else 'Node not found');
    each of its service calls waits up to `service_timeout` (None: the library default)."""
    from ros2lite.graph import node_full_names
    from ros2lite.parameters.remote import RemoteParameters, absolute_node_name, wait_for_node

    fqn = absolute_node_name(node_name)
    found = wait_for_node(
        lambda: node_full_names(session.entities(), include_hidden=True),
        fqn,
        include_hidden_nodes,
        timeout,
    )
    if not found:
        raise CliError("Node not found")
    return RemoteParameters(session.node(), fqn, service_timeout=service_timeout)


def complete_parameter_names(
    ctx: click.Context, _param: click.Parameter, incomplete: str
) -> list[Any]:
    """Names of the node's parameters, asked of the node itself; quick, quiet and without
    starting the daemon, like the other completers (nothing when anything fails)."""
    from click.shell_completion import CompletionItem

    try:
        names = _remote_parameter_names(ctx)
    except Exception:
        return []
    return [CompletionItem(n) for n in sorted(names) if n.startswith(incomplete)]


def _remote_parameter_names(ctx: click.Context) -> list[str]:
    from ros2lite.context import Context
    from ros2lite.daemon.probe import router_answers
    from ros2lite.node import Node
    from ros2lite.parameters.remote import RemoteParameters
    from ros2lite.transport.config import router_endpoint

    node_name = ctx.params.get("node_name")
    router = ctx.find_root().params.get("router")
    if not node_name or not router_answers(router_endpoint(router), timeout=0.3):
        return []
    context = Context().init([], router=router)
    try:
        node = Node(
            "_ros2lite_completion",
            context=context,
            enable_rosout=False,
            use_global_arguments=False,
            start_parameter_services=False,
        )
        remote = RemoteParameters(node, node_name, service_timeout=1.0)
        if not remote.wait_for_services(1.0, ["list_parameters"]):
            return []
        return list(remote.list_parameters().names)
    finally:
        context.try_shutdown()


def type_name(type_number: int) -> str:
    return TYPE_NAMES.get(type_number, f"unknown ({type_number})")
