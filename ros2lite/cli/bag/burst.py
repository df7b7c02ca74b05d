"""`bag burst`: publish a bag's messages as fast as possible, ignoring their recorded timing.

Used to feed a pipeline from a bag at full speed (e.g. to fill a buffer, or to test how a node
copes with a flood). `-n` bursts that many messages (0: all); Ctrl-C stops early, exit status 0.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import click

from .. import numbers
from ..options import bind
from ..parsing import command
from .options import (
    bag_argument,
    bag_error,
    bag_names,
    bag_player,
    play_options,
    player_node_option,
    qos_overrides_option,
    read_ahead_option,
    remap_option,
    services_option,
    start_offset_option,
    topics_option,
)

if TYPE_CHECKING:
    from ros2lite.bag.player import PlayOptions
    from ros2lite.node import Node


@command("burst")
@bag_argument
@read_ahead_option(
    "Messages read ahead of publishing (accepted for ros2bag's sake: a burst reads "
    "as it publishes)."
)
@topics_option("Topics to burst (default: all).")
@services_option("Services whose recorded events to burst (default: all).")
@qos_overrides_option("recorded")
@remap_option
@start_offset_option
@click.option(
    "-n",
    "--num-messages",
    type=numbers.Count(min=0, max=2**63 - 1),
    default=0,
    show_default=True,
    help="Messages to burst (0: all).",
)
@player_node_option
@bind(play_options)
def cli(
    options: PlayOptions,
    bag_path: str,
    storage: str | None,
    services: tuple[str, ...],
    qos_profile_overrides_path: str | None,
    remap_rules: tuple[str, ...],
    num_messages: int,
    node_name: str,
) -> None:
    """Burst data from a bag."""
    from ros2lite.bag.errors import BagError
    from ros2lite.service_introspection import event_topic
    from ros2lite.util.process import StopSignals

    def named(node: Node) -> PlayOptions:
        selected = None
        if options.topics or services:
            events = [event_topic(node.resolve_service_name(s)) for s in services]
            selected = bag_names(node, options.topics or []) + events
        return dataclasses.replace(options, topics=selected)

    with bag_player(
        bag_path, storage, node_name, remap_rules, qos_profile_overrides_path, named
    ) as (player, log):
        try:
            with StopSignals(on_stop=player.stop):
                sent = player.burst(num_messages)
        except (BagError, OSError) as e:
            raise bag_error(str(e)) from None
        log.info(f"Burst {sent} message(s)")
