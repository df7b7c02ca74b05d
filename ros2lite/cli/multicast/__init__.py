"""`ros2lite multicast`: check whether the network passes UDP multicast."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'receive': (__name__ + '.receive', 'Receive a single UDP multicast packet'),
    'send': (__name__ + '.send', 'Send a single UDP multicast packet'),
}


cli = command_group('multicast', 'Various multicast related sub-commands.', VERBS)
