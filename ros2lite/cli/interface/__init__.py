"""`ros2lite interface`: browse the ROS types on the search path."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'list': 'List all interface types available',
    'packages': 'Output a list of packages which contain interfaces',
    'package': 'Output a list of available interface types within one package',
    'show': 'Output the interface definition',
    'proto': 'Output an interface prototype',
    'hash': 'Output the RIHS01 type hash of an interface',
}


cli = command_group(__name__, 'Show information about ROS interfaces.', VERBS)
