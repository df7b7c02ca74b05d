"""`pkg executables [pkg] [--full-path]`: `<package> <executable>` lines, sorted.

A C++ demo package that is not installed lists what `run` starts for it (its Python twin's
executables, by its own name), with a note on stderr. A workspace package whose files colcon
would refuse is named in one line on stderr, file and line, and the status is 1; a C++
workspace package gets its line on stderr too, without failing a listing of all.
"""

from __future__ import annotations

import click

from .. import completion, render
from ..errors import CliError
from ..options import json_option
from ..parsing import command


@command('executables')
@click.argument('package_name', required=False, shell_complete=completion.executable_packages)
@click.option('--full-path', is_flag=True, help='Show full path of each executable')
@json_option('[{"package", "name", "path"}…]')
def cli(package_name: str | None, full_path: bool, as_json: bool) -> None:
    """Output a list of package specific executables."""
    from ros2lite.pkg.errors import NotHereError, PackageFileError
    from ros2lite.pkg.executables import (
        equivalent,
        equivalent_executables,
        package_executables,
    )
    from ros2lite.pkg.index import PackageIndex

    index = PackageIndex()
    if package_name is not None and index.find(package_name) is None:
        twin = equivalent(package_name, index)
        if twin is None:
            raise index.not_found(package_name)
        click.echo(
            f'{package_name} (C++) is not installed; these run {twin.name}, its Python '
            'equivalent, and stand-ins bundled with ros2lite',
            err=True,
        )
        rows = [(package_name, exe) for exe in equivalent_executables(package_name, index)]
        if as_json:
            render.print_json(
                [{'package': p, 'name': e.name, 'path': str(e.path())} for p, e in rows]
            )
            return
        for _, exe in rows:
            click.echo(exe.path() if full_path else f'{package_name} {exe.name}')
        return
    packages = (
        list(index.packages().values())
        if package_name is None
        else [index.packages()[package_name]]
    )
    # listing all: a workspace package.xml that could not be read is a failure too
    failures = [str(p) for p in index.problems] if package_name is None else []
    found: list[dict[str, object]] = []
    for pkg in packages:
        try:
            executables = package_executables(pkg)
        except (NotHereError, PackageFileError) as e:
            if package_name is not None:
                raise
            if isinstance(e, NotHereError):  # a C++ package is no failure of the listing
                click.echo(str(e), err=True)
            else:
                failures.append(str(e))
            continue
        for exe in executables:
            if as_json:
                found.append({'package': pkg.name, 'name': exe.name, 'path': str(exe.path())})
            else:
                click.echo(exe.path() if full_path else f'{pkg.name} {exe.name}')
    if as_json and not failures:
        render.print_json(found)
    if failures:
        for failure in failures[:-1]:
            click.echo(failure, err=True)
        raise CliError(failures[-1])
