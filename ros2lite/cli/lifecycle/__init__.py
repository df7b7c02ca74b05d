"""`ros2lite lifecycle`: inspect and drive managed (lifecycle) nodes."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'get': 'Get lifecycle state for one or more nodes',
    'list': 'Output a list of available transitions',
    'nodes': 'Output a list of nodes with lifecycle',
    'set': 'Trigger lifecycle state transition',
}


cli = command_group(__name__, 'Various lifecycle related sub-commands.', VERBS)
