"""`ros2lite component`: component containers and the components they can load."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'list': 'Output a list of running containers and components',
    'load': 'Load a component into a container node',
    'standalone': 'Run a component into its own standalone container node',
    'types': 'Output a list of components registered in the ament index',
    'unload': 'Unload a component from a container node',
}


cli = command_group(__name__, 'Various component related sub-commands.', VERBS)
