"""`bag burst`: publish a bag's messages as fast as possible, ignoring their recorded timing.

Used to feed a pipeline from a bag at full speed (e.g. to fill a buffer, or to test how a node
copes with a flood). `-n` bursts that many messages (0: all); Ctrl-C stops early, exit status 0.
"""

from __future__ import annotations

from pathlib import Path

import click

from .. import completion, numbers
from ..common import ManyValues, connect
from .options import (
    bag_argument,
    bag_error,
    bag_names,
    parse_remaps,
    qos_overrides,
    resolve_remaps,
)


@click.command("burst")
@bag_argument
@click.option(
    "--read-ahead-queue-size",
    type=numbers.Count(min=1, max=1_000_000),
    default=1000,
    show_default=True,
    help="Messages read ahead of publishing (accepted for ros2bag's sake: a burst reads "
    "as it publishes).",
)
@click.option(
    "--topics",
    cls=ManyValues,
    metavar="TOPIC...",
    shell_complete=completion.topics,
    help="Topics to burst (default: all).",
)
@click.option(
    "--services",
    cls=ManyValues,
    metavar="SERVICE...",
    help="Services whose recorded events to burst (default: all).",
)
@click.option(
    "--qos-profile-overrides-path",
    type=click.Path(dir_okay=False),
    help="YAML file of QoS profiles by topic, used instead of the recorded ones.",
)
@click.option("-m", "--remap", cls=ManyValues, metavar="OLD:=NEW...", help="Topic remappings.")
@click.option(
    "--start-offset",
    type=numbers.seconds(),
    default=0.0,
    help="Start this many seconds into the bag.",
)
@click.option(
    "-n",
    "--num-messages",
    type=numbers.Count(min=0, max=2**63 - 1),
    default=0,
    show_default=True,
    help="Messages to burst (0: all).",
)
@click.option("--node-name", default="rosbag2_player", show_default=True, hidden=True)
def cli(
    bag_path: str,
    storage: str | None,
    read_ahead_queue_size: int,
    topics: tuple[str, ...],
    services: tuple[str, ...],
    qos_profile_overrides_path: str | None,
    remap: tuple[str, ...],
    start_offset: float,
    num_messages: int,
    node_name: str,
) -> None:
    """Burst data from a bag."""
    from ros2lite.bag.errors import BagError
    from ros2lite.bag.player import Player, PlayOptions
    from ros2lite.bag.reader import Reader
    from ros2lite.logging import get_logger
    from ros2lite.process import StopSignals
    from ros2lite.service_introspection import event_topic

    if not Path(bag_path).exists():
        raise bag_error(f"Bag path '{bag_path}' does not exist!")
    remaps = parse_remaps(remap)
    overrides = qos_overrides(qos_profile_overrides_path)
    try:
        reader = Reader(bag_path, storage)
    except BagError as e:
        raise bag_error(str(e)) from None
    log = get_logger(node_name)
    with reader, connect() as conn:
        node = conn.node(node_name)
        try:
            selected = None
            if topics or services:
                events = [event_topic(node.resolve_service_name(s)) for s in services]
                selected = bag_names(node, topics) + events
            player = Player(
                node,
                reader,
                PlayOptions(
                    topics=selected,
                    remap=resolve_remaps(node, remaps),
                    start_offset=start_offset,
                    read_ahead_queue_size=read_ahead_queue_size,
                    qos_overrides=overrides,
                ),
                log=lambda m: log.info(m),
                warn=lambda m: log.warn(m),
            )
        except (BagError, ValueError) as e:
            raise bag_error(str(e)) from None
        try:
            with StopSignals(on_stop=player.stop):
                sent = player.burst(num_messages)
        except (BagError, OSError) as e:
            raise bag_error(str(e)) from None
        log.info(f"Burst {sent} message(s)")
