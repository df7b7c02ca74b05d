"""`param list`: parameter names of one node, or of every node (sorted, `/node:` headers)."""

from __future__ import annotations

import re

import click

from .. import render
from ..common import connect
from ..errors import CliError
from ..options import json_option
from ..parsing import ManyValues, command
from .common import Remote, Target, node_options, type_name


@command("list")
@node_options(timeout=False, node_required=False)
@click.option(
    "--filter",
    "filter_regex",
    metavar="REGEX",
    help="Only list parameters whose names match this regular expression",
)
@click.option(
    "--param-prefixes",
    cls=ManyValues,
    metavar="PREFIX...",
    help="Only list parameters with the provided prefixes",
)
@click.option("--param-type", is_flag=True, help="Print parameter types with parameter names")
@json_option('{"/node": [{"name", "type"}…]} (type null without --param-type)')
def cli(
    filter_regex: str | None,
    param_prefixes: tuple[str, ...],
    param_type: bool,
    target: Target,
    as_json: bool,
) -> None:
    """Output a list of available parameters."""
    from ros2lite.graph import node_full_names, service_names_and_types
    from ros2lite.names import absolute_node_name

    try:
        pattern = re.compile(filter_regex) if filter_regex is not None else None
    except re.error as e:
        raise CliError(f"Invalid regular expression '{filter_regex}': {e}") from None
    doc: dict[str, object] = {}
    with connect(no_daemon=target.no_daemon, use_sim_time=target.use_sim_time) as conn:
        entities = conn.entities()
        nodes = sorted(set(node_full_names(entities, include_hidden=target.include_hidden_nodes)))
        if target.node_name is not None:
            wanted = absolute_node_name(target.node_name)
            if wanted not in nodes:
                raise CliError("Node not found")
            nodes = [wanted]
        services = {name for name, _ in service_names_and_types(entities, include_hidden=True)}
        for fqn in nodes:
            if f"{fqn}/list_parameters" not in services:
                continue  # a node without parameter services (e.g. another CLI's)
            remote = Remote(conn, fqn, None)
            try:
                names = sorted(remote.call("list_parameters", param_prefixes).result.names)
                if pattern is not None:
                    names = [n for n in names if pattern.match(n)]
                types = {}
                if param_type and names:
                    descriptors = remote.call("describe_parameters", names).descriptors
                    types = {d.name: type_name(d.type) for d in descriptors}
            except CliError as e:
                click.echo(str(e), err=True)
                continue
            if as_json:
                doc[fqn] = [{"name": n, "type": types.get(n)} for n in names]
                continue
            if target.node_name is None:
                render.echo(f"{fqn}:")
            for name in names:
                render.echo(
                    f"  {name} (type: {types.get(name, 'not set')})" if param_type else f"  {name}"
                )
    if as_json:
        render.print_json(doc)
