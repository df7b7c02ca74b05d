"""`ros2lite srv`: ros2cli's deprecated service listing (use `interface`)."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'list': (__name__ + '.list', 'Output a list of available service types'),
    'package': (
        __name__ + '.package',
        'Output a list of available service types within one package',
    ),
    'packages': (__name__ + '.packages', 'Output a list of packages which contain srvs'),
    'show': (__name__ + '.show', 'Output the service definition'),
}

cli = command_group('srv', 'Various srv related sub-commands.', VERBS)
