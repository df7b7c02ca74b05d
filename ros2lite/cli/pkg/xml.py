"""`pkg xml <pkg> [-t TAG]`: the package manifest as ros2pkg prints it."""

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

    from ros2lite.pkg.index import PackageIndex

    pkg = PackageIndex().find(package_name)
    if pkg is None:
        raise CliError('Package not found')
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
