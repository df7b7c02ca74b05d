"""`pkg executables [pkg] [--full-path]`: `<package> <executable>` lines, sorted."""

from __future__ import annotations

import click

from .. import completion
from ..parsing import command


@command('executables')
@click.argument('package_name', required=False, shell_complete=completion.executable_packages)
@click.option('--full-path', is_flag=True, help='Show full path of each executable')
def cli(package_name: str | None, full_path: bool) -> None:
    """Output a list of package specific executables."""
    from ros2lite.pkg.executables import (
        PackageNotFoundError,
        package_executables,
    )
    from ros2lite.pkg.index import PackageIndex

    index = PackageIndex()
    if package_name is None:
        packages = list(index.packages().values())
    else:
        pkg = index.find(package_name)
        if pkg is None:
            raise PackageNotFoundError(package_name, list(index.packages()))
        packages = [pkg]
    for pkg in packages:
        for exe in package_executables(pkg):
            click.echo(exe.path() if full_path else f'{pkg.name} {exe.name}')
