"""`ros2lite msg`: ros2cli's deprecated message listing (use `interface`)."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'list': (__name__ + '.list', 'Output a list of available message types'),
    'package': (
        __name__ + '.package',
        'Output a list of available message types within one package',
    ),
    'packages': (__name__ + '.packages', 'Output a list of packages which contain msgs'),
    'show': (__name__ + '.show', 'Output the message definition'),
}

cli = command_group('msg', 'Various msg related sub-commands.', VERBS)
