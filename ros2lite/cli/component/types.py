"""`component types`: the components this machine can load, by package."""

from __future__ import annotations

import click

from .. import render
from ..errors import CliError
from ..options import json_option
from ..parsing import command


@command('types')
@click.argument('package_name', required=False)
@json_option('{"package": ["plugin", …]} (PACKAGE_NAME: its list of plugins)')
def cli(package_name: str | None, as_json: bool) -> None:
    """Output a list of components registered in the ament index.

    ros2lite's own (the composition demo's), Python packages' `ros2lite.components` entry
    points and the ament index's `rclpy_components`/`rclcpp_components` resources.
    """
    from ros2lite.components.registry import component_types
    from ros2lite.pkg.executables import list_packages

    types = component_types()
    if package_name is not None:
        if package_name not in types and package_name not in list_packages():
            raise CliError(f"Unable to find package '{package_name}'")
        if as_json:
            render.print_json([c.plugin for c in types.get(package_name, [])])
            return
        for component in types.get(package_name, []):
            click.echo(component.plugin)
        return
    if as_json:
        render.print_json({p: [c.plugin for c in cs] for p, cs in types.items()})
        return
    for package, components in types.items():
        click.echo(package)
        for component in components:
            click.echo(f'  {component.plugin}')
