"""`ros2lite daemon`: the local Zenoh router that every ros2lite session connects to."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'start': (__name__ + '.start', 'Start the daemon if it isn\'t running'),
    'status': (__name__ + '.status', 'Output the status of the daemon'),
    'stop': (__name__ + '.stop', 'Stop the daemon if it is running'),
}


cli = command_group('daemon', 'Various daemon related sub-commands.', VERBS)
