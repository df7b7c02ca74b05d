"""`bag play`: publish a bag's messages with their recorded timing and QoS.

On a terminal: a progress line on stderr and keys (SPACE pause/resume, → next message,
↑/↓ rate ±10 %). Ctrl-C or SIGTERM stops playing; exit status 0.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path
from typing import TYPE_CHECKING

import click

from .. import completion, render
from .. import keyboard as keys_module
from ..common import ManyValues, connect
from .options import bag_argument, bag_error, check_patterns, qos_overrides, shared_options

if TYPE_CHECKING:
    from collections.abc import Iterable

    from ros2lite.bag.player import Player
    from ros2lite.logging import RcutilsLogger
    from ros2lite.node import Node


@click.command("play")
@bag_argument
@click.option(
    "--read-ahead-queue-size",
    type=click.IntRange(min=1),
    default=1000,
    show_default=True,
    help="Messages read ahead of playback.",
)
@click.option(
    "-r",
    "--rate",
    type=click.FloatRange(min=0, min_open=True),
    default=1.0,
    show_default=True,
    help="Rate at which to play back messages.",
)
@click.option(
    "--topics",
    cls=ManyValues,
    metavar="TOPIC...",
    shell_complete=completion.topics,
    help="Topics to play (default: all).",
)
@shared_options("play", "recorded", "-p")
@click.option("-l", "--loop", is_flag=True, help="Play the bag again and again.")
@click.option("-m", "--remap", cls=ManyValues, metavar="OLD:=NEW...", help="Topic remappings.")
@click.option(
    "--clock",
    "clock_hz",
    type=click.FloatRange(min=0),
    is_flag=False,
    flag_value=40.0,
    default=0.0,
    metavar="[HZ]",
    help="Publish /clock at HZ (40 when given alone) with the bag time.",
)
@click.option(
    "-d",
    "--delay",
    type=click.FloatRange(min=0),
    default=0.0,
    help="Seconds to wait before playing (again before each loop).",
)
@click.option(
    "--start-offset",
    type=click.FloatRange(min=0),
    default=0.0,
    help="Start this many seconds into the bag.",
)
@click.option("--node-name", default="rosbag2_player", show_default=True, hidden=True)
def cli(
    bag_path: str,
    storage: str | None,
    read_ahead_queue_size: int,
    rate: float,
    topics: tuple[str, ...],
    regex: str | None,
    exclude_regex: str | None,
    exclude_topics: tuple[str, ...],
    qos_profile_overrides_path: str | None,
    loop: bool,
    remap: tuple[str, ...],
    clock_hz: float,
    delay: float,
    start_offset: float,
    start_paused: bool,
    disable_keyboard_controls: bool,
    node_name: str,
) -> None:
    """Play back ROS data from a bag."""
    from ros2lite.bag.errors import BagError
    from ros2lite.bag.player import Player, PlayOptions
    from ros2lite.bag.reader import Reader

    if not Path(bag_path).exists():
        raise bag_error(f"Bag path '{bag_path}' does not exist!")
    check_patterns(regex, exclude_regex)
    remaps = {}
    for rule in remap:
        old, sep, new = rule.partition(":=")
        if not sep or not old or not new:
            raise bag_error(f"Remapping '{rule}' is not OLD:=NEW")
        remaps[old] = new
    overrides = qos_overrides(qos_profile_overrides_path)
    try:
        reader = Reader(bag_path, storage)
    except BagError as e:
        raise bag_error(str(e)) from None
    from ros2lite.logging import get_logger

    log = get_logger(node_name)
    with reader, connect() as conn:
        node = conn.node(node_name)
        try:
            names = _absolute(node, topics) if topics else None
            options = PlayOptions(
                rate=rate,
                loop=loop,
                topics=names,
                exclude_topics=_absolute(node, exclude_topics),
                regex=regex,
                exclude_regex=exclude_regex,
                remap={
                    old: node.resolve_topic_name(new)
                    for k, new in remaps.items()
                    for old in _absolute(node, [k])
                },
                start_offset=start_offset,
                delay=delay,
                clock_hz=clock_hz,
                start_paused=start_paused,
                read_ahead_queue_size=read_ahead_queue_size,
                qos_overrides=overrides,
            )
            player = Player(
                node, reader, options, log=lambda m: log.info(m), warn=lambda m: log.warn(m)
            )
        except (BagError, ValueError) as e:
            raise bag_error(str(e)) from None
        _play(player, log, keyboard=not disable_keyboard_controls)


def _absolute(node: Node, names: Iterable[str]) -> list[str]:
    """Every form a given name may have in the bag: resolved (`/ns/x`) and, for relative
    names, as written (rosbag2 test bags hold names such as 'AAA')."""
    out = []
    for n in names:
        try:
            out.append(node.resolve_topic_name(n))
        except ValueError:
            out.append(n)  # rosbag2 bags may hold names ROS would not accept (e.g. 'AAA')
        if not n.startswith("/"):
            out.append(n)
    return out


def _play(player: Player, log: RcutilsLogger, keyboard: bool) -> None:
    from ros2lite.bag.errors import BagError
    from ros2lite.bag.player import SWITCH_INTERVAL
    from ros2lite.process import StopSignals, switch_interval

    keys = None
    if keyboard and keys_module.available() and sys.stderr.isatty():
        log.info("Adding keyboard callbacks.")
        log.info("Press SPACE for Pause/Resume")
        log.info("Press CURSOR_RIGHT for Play Next Message")
        log.info("Press CURSOR_UP for Increase Rate 10%")
        log.info("Press CURSOR_DOWN for Decrease Rate 10%")
        keys = keys_module.Keyboard(
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
