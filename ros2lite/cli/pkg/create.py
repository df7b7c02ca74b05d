"""`pkg create <name>`: ros2pkg's options, progress lines and warnings."""

from __future__ import annotations

import os

import click

from ..errors import CliError
from ..parsing import ManyValues, command


@command('create')
@click.argument('package_name')
@click.option(
    '--package-format',
    '--package_format',
    type=click.Choice(['2', '3']),
    default='3',
    show_default=True,
    help='The package.xml format.',
)
@click.option(
    '--description',
    default='TODO: Package description',
    show_default=True,
    help='The description given in the package.xml',
)
@click.option(
    '--license',
    'license_',
    default='TODO: License declaration',
    show_default=True,
    help='The license attached to this package; this can be an arbitrary string, but a '
    "LICENSE file will only be generated if it is one of the supported licenses (pass '?' "
    'to get a list)',
)
@click.option(
    '--destination-directory',
    default=os.curdir,
    show_default=True,
    help='Directory where to create the package directory',
)
@click.option(
    '--build-type',
    type=click.Choice(['cmake', 'ament_cmake', 'ament_python']),
    default='ament_cmake',
    show_default=True,
    help='The build type to process the package with',
)
@click.option(
    '--dependencies',
    cls=ManyValues,
    metavar='DEP...',
    help='list of dependencies',
)
@click.option('--maintainer-email', help='email address of the maintainer of this package')
@click.option('--maintainer-name', help='name of the maintainer of this package')
@click.option('--node-name', help='name of the empty executable')
@click.option('--library-name', help='name of the empty library')
def cli(
    package_name: str,
    package_format: str,
    description: str,
    license_: str,
    destination_directory: str,
    build_type: str,
    dependencies: tuple[str, ...],
    maintainer_email: str | None,
    maintainer_name: str | None,
    node_name: str | None,
    library_name: str | None,
) -> None:
    """Create a new ROS 2 package."""
    from ros2lite.pkg.create import (
        LICENSES,
        PackageSpec,
        create_package,
        default_maintainer,
        prepare_spec,
    )

    if license_ == '?':
        click.echo('Supported licenses:\n' + '\n'.join(LICENSES))
        return
    name, email = default_maintainer(maintainer_name)
    email = maintainer_email or email
    spec, warnings = prepare_spec(
        PackageSpec(
            name=package_name,
            build_type=build_type,
            package_format=int(package_format),
            description=description,
            license=license_,
            maintainer_name=name,
            maintainer_email=email,
            dependencies=dependencies,
            node_name=node_name,
            library_name=library_name,
        )
    )
    if os.path.lexists(os.path.join(destination_directory, spec.name)):
        raise CliError(
            f'\nAborted!\nThe directory already exists: '
            f'{os.path.join(destination_directory, spec.name)}\n'
            'Either remove the directory or choose a different destination directory or '
            'package name'
        )
    for line in warnings:
        click.echo(line, err=True)
    click.echo('going to create a new package')
    click.echo(f'package name: {spec.name}')
    click.echo(f'destination directory: {os.path.abspath(destination_directory)}')
    click.echo(f'package format: {spec.package_format}')
    click.echo(f'version: {spec.version}')
    click.echo(f'description: {spec.description}')
    click.echo(f'maintainer: {[f"{spec.maintainer_name} <{spec.maintainer_email}>"]}')
    click.echo(f'licenses: {[spec.license]}')
    click.echo(f'build type: {spec.build_type}')
    click.echo(f'dependencies: {list(spec.dependencies)}')
    if spec.node_name:
        click.echo(f'node_name: {spec.node_name}')
    if spec.library_name:
        click.echo(f'library_name: {spec.library_name}')
    created = create_package(spec, destination_directory, click.echo)
    if not created.license_file:
        click.echo(
            f"\n[WARNING]: Unknown license '{spec.license}'.  This has been set in the "
            'package.xml, but no LICENSE file has been created.\nIt is recommended to use one '
            'of the ament license identifiers:\n' + '\n'.join(LICENSES)
        )
