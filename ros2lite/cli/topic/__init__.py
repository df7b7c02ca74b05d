"""`ros2lite topic`: inspect and exercise topics."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    'bw': 'Display bandwidth used by topic',
    'delay': 'Display delay of topic from timestamp in header',
    'echo': 'Output messages from a topic',
    'find': 'Output a list of available topics of a given type',
    'hz': 'Print the average publishing rate to screen',
    'info': 'Print information about a topic',
    'list': 'Output a list of available topics',
    'plot': 'Plot numeric fields of topics live, in the terminal or to a picture',
    'pub': 'Publish a message to a topic',
    'type': "Print a topic's type",
}

cli = command_group(__name__, 'Various topic related sub-commands.', VERBS, hidden='topics')
