"""`ros2lite action`: inspect actions and send them goals."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'echo': (__name__ + '.echo', 'Echo a action'),
    'find': (__name__ + '.find', 'Find actions from type'),
    'info': (__name__ + '.info', 'Print information about an action'),
    'list': (__name__ + '.list', 'Output a list of action names'),
    'send_goal': (__name__ + '.send_goal', 'Send an action goal'),
    'type': (__name__ + '.type', "Print a action's type"),
}

cli = command_group('action', 'Various action related sub-commands.', VERBS)
