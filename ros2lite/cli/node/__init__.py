"""`ros2lite node`: the nodes in the graph."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'info': 'Output information about a node',
    'list': 'Output a list of available nodes',
}


cli = command_group(__name__, 'Various node related sub-commands.', VERBS)
