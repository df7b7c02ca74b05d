"""`ros2lite pkg`: the packages ros2lite can see — installed, bundled and in source
workspaces — and a new package's skeleton."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'create': 'Create a new ROS 2 package',
    'executables': 'Output a list of package specific executables',
    'list': 'Output a list of available packages',
    'prefix': 'Output the prefix path of a package',
    'xml': 'Output the XML of the package manifest or a specific tag',
}

cli = command_group(__name__, 'Various package related sub-commands.', VERBS)
