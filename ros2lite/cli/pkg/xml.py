"""`pkg xml <pkg> [-t TAG]`: the package manifest as ros2pkg prints it (a C++ demo package
that is not installed: its Python twin's, with a note on stderr)."""

from __future__ import annotations

import click

from .. import completion
from ..errors import CliError
from ..parsing import command


@command('xml')
@click.argument('package_name', shell_complete=completion.executable_packages)
@click.option('-t', '--tag', help="The package's xml's tag to print")
def cli(package_name: str, tag: str | None) -> None:
    """Output the XML of the package manifest or a specific tag."""
    import xml.etree.ElementTree as ET

    from ros2lite.pkg.executables import equivalent
    from ros2lite.pkg.index import PackageIndex

    index = PackageIndex()
    pkg = index.find(package_name)
    if pkg is None:
        pkg = equivalent(package_name, index)
        if pkg is None:
            raise index.not_found(package_name, 'Package not found')
        click.echo(
            f'{package_name} (C++) is not installed; this is {pkg.name}, its Python equivalent',
            err=True,
        )
    path = pkg.manifest_path
    if path is None:
        raise CliError('Package XML manifest not found')
    try:
        tree = ET.parse(path)
    except (ET.ParseError, OSError) as e:
        raise CliError(f'{path}: {e}') from None
    if tag is None:
        # ElementTree's own serialisation, as `ET.dump` gives ros2pkg
        click.echo(ET.tostring(tree.getroot(), encoding='unicode').rstrip('\n'))
        return
    try:
        elements = tree.getroot().findall(tag)
    except SyntaxError as e:  # a malformed path expression
        raise CliError(f"invalid tag '{tag}': {e}") from None
    if not elements:
        raise CliError('XML tag not found')
    for element in elements:
        click.echo(str(element.text))
