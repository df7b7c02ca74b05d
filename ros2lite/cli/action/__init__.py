"""`ros2lite action`: inspect actions and send them goals."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'echo': 'Echo a action',
    'find': 'Find actions from type',
    'info': 'Print information about an action',
    'list': 'Output a list of action names',
    'send_goal': 'Send an action goal',
    'type': "Print a action's type",
}

cli = command_group(__name__, 'Various action related sub-commands.', VERBS)
