"""`ros2lite interface`: browse the ROS types on the search path."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'list': (__name__ + '.list', 'List all interface types available'),
    'packages': (__name__ + '.packages', 'Output a list of packages which contain interfaces'),
    'package': (
        __name__ + '.package',
        'Output a list of available interface types within one package',
    ),
    'show': (__name__ + '.show', 'Output the interface definition'),
    'proto': (__name__ + '.proto', 'Output an interface prototype'),
    'hash': (__name__ + '.hash', 'Output the RIHS01 type hash of an interface'),
}


cli = command_group('interface', 'Show information about ROS interfaces.', VERBS)
