"""`ros2lite lifecycle`: inspect and drive managed (lifecycle) nodes."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'get': (__name__ + '.get', 'Get lifecycle state for one or more nodes'),
    'list': (__name__ + '.list', 'Output a list of available transitions'),
    'nodes': (__name__ + '.nodes', 'Output a list of nodes with lifecycle'),
    'set': (__name__ + '.set', 'Trigger lifecycle state transition'),
}


cli = command_group('lifecycle', 'Various lifecycle related sub-commands.', VERBS)
