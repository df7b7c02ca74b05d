"""`ros2lite node`: the nodes in the graph."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'info': (__name__ + '.info', 'Output information about a node'),
    'list': (__name__ + '.list', 'Output a list of available nodes'),
}


cli = command_group('node', 'Various node related sub-commands.', VERBS)
