"""`pkg xml <pkg> [-t TAG]`: the package manifest as ros2pkg prints it (a C++ demo package
that is not installed: its Python twin's, with a note on stderr)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import click

from .. import completion, render
from ..errors import CliError
from ..options import json_option
from ..parsing import command

if TYPE_CHECKING:
    from xml.etree.ElementTree import Element


def element_json(element: Element) -> dict[str, object]:
    """An XML element as `pkg xml --json` prints it: tag, attributes, its text (stripped;
    null when only whitespace) and its child elements in order, so nothing of a manifest is
    lost and a script needs no XML parser."""
    text = (element.text or '').strip()
    return {
        'tag': element.tag,
        'attributes': dict(element.attrib),
        'text': text or None,
        'children': [element_json(child) for child in element],
    }


@command('xml')
@click.argument('package_name', shell_complete=completion.executable_packages)
@click.option('-t', '--tag', help="The package's xml's tag to print")
@json_option(
    'the manifest as {"tag", "attributes", "text", "children"} elements '
    '(with -t: the list of the tags\' texts)'
)
def cli(package_name: str, tag: str | None, as_json: bool) -> None:
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
    if tag is None and as_json:
        render.print_json(element_json(tree.getroot()))
        return
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
    if as_json:
        render.print_json([element.text for element in elements])
        return
    for element in elements:
        click.echo(str(element.text))
