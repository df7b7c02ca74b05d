"""`bag play`: publish a bag's messages with their recorded timing and QoS.

On a terminal: a progress line on stderr and keys (SPACE pause/resume, → next message,
↑/↓ rate ±10 %). Ctrl-C or SIGTERM stops playing; exit status 0.
"""

from __future__ import annotations

import dataclasses
import sys
import time
from typing import TYPE_CHECKING

import click

from ros2lite.util import keyboard as keys_module

from .. import numbers, render
from ..options import bind
from ..parsing import command
from .options import (
    bag_argument,
    bag_error,
    bag_names,
    bag_player,
    play_options,
    player_node_option,
    read_ahead_option,
    remap_option,
    shared_options,
    start_offset_option,
    topics_option,
)

if TYPE_CHECKING:
    from ros2lite.bag.player import Player, PlayOptions
    from ros2lite.logging import RcutilsLogger
    from ros2lite.node import Node


@command("play")
@bag_argument
@read_ahead_option("Messages read ahead of playback.")
@click.option(
    "-r",
    "--rate",
    type=numbers.rate(),
    default=1.0,
    show_default=True,
    help="Rate at which to play back messages.",
)
@topics_option("Topics to play (default: all).")
@shared_options("play", "recorded", "-p")
@click.option("-l", "--loop", is_flag=True, help="Play the bag again and again.")
@remap_option
@click.option(
    "--clock",
    "clock_hz",
    type=numbers.Finite(min=0, max=numbers.MAX_RATE),
    is_flag=False,
    flag_value=40.0,
    default=0.0,
    metavar="[HZ]",
    help="Publish /clock at HZ (40 when given alone) with the bag time.",
)
@click.option(
    "-d",
    "--delay",
    type=numbers.seconds(),
    default=0.0,
    help="Seconds to wait before playing (again before each loop).",
)
@start_offset_option
@player_node_option
@bind(play_options)
def cli(
    options: PlayOptions,
    bag_path: str,
    storage: str | None,
    qos_profile_overrides_path: str | None,
    remap_rules: tuple[str, ...],
    disable_keyboard_controls: bool,
    node_name: str,
) -> None:
    """Play back ROS data from a bag."""

    def named(node: Node) -> PlayOptions:
        return dataclasses.replace(
            options,
            topics=bag_names(node, options.topics) if options.topics else None,
            exclude_topics=bag_names(node, options.exclude_topics),
        )

    with bag_player(
        bag_path,
        storage,
        node_name,
        remap_rules,
        qos_profile_overrides_path,
        named,
        patterns=(options.regex, options.exclude_regex),
    ) as (player, log):
        _play(player, log, keyboard=not disable_keyboard_controls)


def _play(player: Player, log: RcutilsLogger, keyboard: bool) -> None:
    from ros2lite.bag.errors import BagError
    from ros2lite.bag.player import SWITCH_INTERVAL
    from ros2lite.util.process import StopSignals, switch_interval

    keys = None
    if keyboard and keys_module.available() and sys.stderr.isatty():
        log.info("Adding keyboard callbacks.")
        log.info("Press SPACE for Pause/Resume")
        log.info("Press CURSOR_RIGHT for Play Next Message")
        log.info("Press CURSOR_UP for Increase Rate 10%")
        log.info("Press CURSOR_DOWN for Decrease Rate 10%")
        keys = keys_module.KeyHandlers(
            {
                " ": player.toggle_paused,
                "right": player.play_next,
                "up": lambda: player.set_rate(round(player.rate + 0.1, 6)),
                "down": lambda: player.set_rate(round(player.rate - 0.1, 6)),
            }
        )
    log.info("Playback until timestamp: -1")
    progress = _Progress(player) if render.fancy(sys.stderr) else None
    try:
        # this process plays on time: a message due must not wait for the read-ahead thread
        with switch_interval(SWITCH_INTERVAL), StopSignals() as stop:
            player.run(stop.event, on_tick=progress.update if progress is not None else None)
    except (BagError, OSError, ValueError) as e:
        raise bag_error(str(e)) from None
    finally:
        if progress is not None:
            progress.close()
        if keys is not None:
            keys.close()


class _Progress:
    """One status line on stderr: bag time, elapsed/total and state."""

    def __init__(self, player: Player) -> None:
        self.player = player
        self.start = player.reader.start_time
        self.total = max(player.reader.metadata.duration, 1)
        self._last = 0.0
        self._line = render.ProgressLine()

    def update(self) -> None:
        now = time.monotonic()
        if now - self._last < 0.1:
            return
        self._last = now
        t = self.player.bag_time()
        done = min(max(t - self.start, 0), self.total)
        width = 30
        filled = int(width * done / self.total)
        state = "P" if self.player.paused else "R"
        sec, nsec = divmod(t, 1_000_000_000)
        self._line.show(
            f"[{'#' * filled}{'-' * (width - filled)}] [{sec}.{nsec // 1_000_000:03d}] "
            f"Duration {done / 1e9:.2f}/{self.total / 1e9:.2f} [{state}] "
            f"x{self.player.rate:g}  "
        )

    def close(self) -> None:
        self._line.close()
