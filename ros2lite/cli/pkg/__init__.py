"""`ros2lite pkg`: the packages ros2lite can see — installed, bundled and in source
workspaces — and a new package's skeleton."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'create': (__name__ + '.create', 'Create a new ROS 2 package'),
    'executables': (__name__ + '.executables', 'Output a list of package specific executables'),
    'list': (__name__ + '.list', 'Output a list of available packages'),
    'prefix': (__name__ + '.prefix', 'Output the prefix path of a package'),
    'xml': (__name__ + '.xml', 'Output the XML of the package manifest or a specific tag'),
}


cli = command_group('pkg', 'Various package related sub-commands.', VERBS)
