"""`ros2lite component`: component containers and the components they can load."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'list': (__name__ + '.list', 'Output a list of running containers and components'),
    'load': (__name__ + '.load', 'Load a component into a container node'),
    'standalone': (
        __name__ + '.standalone',
        'Run a component into its own standalone container node',
    ),
    'types': (__name__ + '.types', 'Output a list of components registered in the ament index'),
    'unload': (__name__ + '.unload', 'Unload a component from a container node'),
}


cli = command_group('component', 'Various component related sub-commands.', VERBS)
