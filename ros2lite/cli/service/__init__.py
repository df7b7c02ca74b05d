"""`ros2lite service`: inspect and call services."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'call': 'Call a service',
    'echo': 'Echo a service',
    'find': 'Output a list of available services of a given type',
    'info': 'Print information about a service',
    'list': 'Output a list of available services',
    'type': "Output a service's type",
}

cli = command_group(__name__, 'Various service related sub-commands.', VERBS, hidden='services')
