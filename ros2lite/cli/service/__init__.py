"""`ros2lite service`: inspect and call services."""

from __future__ import annotations

import click

from ..lazy import LazyGroup

VERBS = {
    'call': (__name__ + '.call', 'Call a service'),
    'echo': (__name__ + '.echo', 'Echo a service'),
    'find': (__name__ + '.find', 'Output a list of available services of a given type'),
    'info': (__name__ + '.info', 'Print information about a service'),
    'list': (__name__ + '.list', 'Output a list of available services'),
    'type': (__name__ + '.type', "Output a service's type"),
}


@click.group(cls=LazyGroup, lazy=VERBS, invoke_without_command=True)
@click.option('--include-hidden-services', is_flag=True, help='Consider hidden services as well')
@click.pass_context
def cli(ctx: click.Context, include_hidden_services: bool) -> None:
    """Various service related sub-commands."""
    ctx.ensure_object(dict)['include_hidden_services'] = include_hidden_services
    if ctx.invoked_subcommand is None:
        click.echo(ctx.get_help())


def hidden_wanted(ctx: click.Context, flag: bool = False) -> bool:
    """--include-hidden-services given on the verb or on `service` itself."""
    return flag or bool((ctx.obj or {}).get('include_hidden_services'))
