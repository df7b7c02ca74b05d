"""`component types`: the components this machine can load, by package."""

from __future__ import annotations

import click

from ..errors import CliError
from ..parsing import command


@command('types')
@click.argument('package_name', required=False)
def cli(package_name: str | None) -> None:
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
        for component in types.get(package_name, []):
            click.echo(component.plugin)
        return
    for package, components in types.items():
        click.echo(package)
        for component in components:
            click.echo(f'  {component.plugin}')
