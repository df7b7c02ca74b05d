"""`ros2lite daemon`: the local Zenoh router that every ros2lite session connects to."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'start': "Start the daemon if it isn't running",
    'status': 'Output the status of the daemon',
    'stop': 'Stop the daemon if it is running',
}


cli = command_group(__name__, 'Various daemon related sub-commands.', VERBS)
