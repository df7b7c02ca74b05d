"""`pkg prefix <pkg> [--share]`: where a package lives, and (on stderr) which source won
when that is not simply an installed prefix, or which Python twin stands in for a C++ demo
package that is not installed."""

from __future__ import annotations

import click

from .. import completion, render
from ..errors import CliError
from ..options import json_option
from ..parsing import command


@command('prefix')
@click.argument('package_name', shell_complete=completion.executable_packages)
@click.option('--share', is_flag=True, help='Show share directory for the package')
@json_option('{"package", "prefix", "share"} (paths; share null when there is none)')
def cli(package_name: str, share: bool, as_json: bool) -> None:
    """Output the prefix path of a package."""
    from ros2lite.pkg.executables import equivalent
    from ros2lite.pkg.index import ORIGIN_AMENT, PackageIndex

    index = PackageIndex()
    candidates = index.candidates(package_name)
    twin = equivalent(package_name, index) if not candidates else None
    if twin is not None and as_json:
        render.print_json(
            {'package': package_name, 'prefix': str(twin.prefix), 'share': str(twin.share)}
        )
    elif twin is not None:
        click.echo(str(twin.share if share else twin.prefix))
    if twin is not None:
        click.echo(
            f'{package_name} (C++) is not installed; this is {twin.name}, its Python equivalent',
            err=True,
        )
        return
    if not candidates:
        raise index.not_found(package_name, 'Package not found')
    winner, shadowed = candidates[0], candidates[1:]
    path = winner.share if share else winner.prefix
    if as_json:
        render.print_json(
            {
                'package': package_name,
                'prefix': str(winner.prefix),
                'share': None if winner.share is None else str(winner.share),
            }
        )
    elif path is None:
        raise CliError(f"Package '{package_name}' has no share directory")
    else:
        click.echo(str(path))
    if winner.origin != ORIGIN_AMENT or shadowed:
        note = f'{package_name}: from the {winner.describe_source()}'
        if shadowed:
            note += '; shadows the ' + ', the '.join(p.describe_source() for p in shadowed)
        click.echo(note, err=True)
