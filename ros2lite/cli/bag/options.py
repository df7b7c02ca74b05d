"""What the bag verbs share: options of record, play and burst, ros2bag's error lines, QoS
overrides, and the player that play and burst set up alike."""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterable, Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

import click

from .. import completion, numbers
from ..errors import CliError
from ..parsing import ManyValues

if TYPE_CHECKING:
    from ros2lite.bag.player import Player, PlayOptions
    from ros2lite.bag.recorder import RecordOptions
    from ros2lite.logging import RcutilsLogger
    from ros2lite.node import Node
    from ros2lite.qos import QoSProfile

F = TypeVar("F", bound=Callable[..., Any])

# the storage plugins' ids (the keys of ros2lite.bag.storage.PLUGINS), written out so that
# parsing a bag verb's options imports no bag code
STORAGE_IDS = ("mcap", "sqlite3", "rosbag1")

# -m/--remap, --start-offset and the player's (hidden) node name: play and burst alike
remap_option = click.option(
    "-m",
    "--remap",
    "remap_rules",
    cls=ManyValues,
    metavar="OLD:=NEW...",
    help="Topic remappings.",
)
start_offset_option = click.option(
    "--start-offset",
    type=numbers.seconds(),
    default=0.0,
    help="Start this many seconds into the bag.",
)
player_node_option = click.option(
    "--node-name", default="rosbag2_player", show_default=True, hidden=True
)


def play_options() -> type[PlayOptions]:
    """The library's play options, for `bind` (imported when the verb runs)."""
    from ros2lite.bag.player import PlayOptions

    return PlayOptions


def record_options() -> type[RecordOptions]:
    """The library's record options, for `bind` (imported when the verb runs)."""
    from ros2lite.bag.recorder import RecordOptions

    return RecordOptions


def read_ahead_option(help: str) -> Callable[[F], F]:
    """--read-ahead-queue-size of play and burst (`help` says what it means for the verb)."""
    return click.option(
        "--read-ahead-queue-size",
        type=numbers.Count(min=1, max=1_000_000),
        default=1000,
        show_default=True,
        help=help,
    )


def topics_option(help: str) -> Callable[[F], F]:
    """--topics TOPIC... (completed from the graph) of record, play and burst."""
    return click.option(
        "--topics",
        cls=ManyValues,
        metavar="TOPIC...",
        shell_complete=completion.topics,
        help=help,
    )


def services_option(help: str) -> Callable[[F], F]:
    """--services SERVICE... of record and burst."""
    return click.option("--services", cls=ManyValues, metavar="SERVICE...", help=help)


def qos_overrides_option(source: str) -> Callable[[F], F]:
    """--qos-profile-overrides-path, whose profiles replace the `source` ('offered',
    'recorded') ones."""
    return click.option(
        "--qos-profile-overrides-path",
        type=click.Path(dir_okay=False),
        help=f"YAML file of QoS profiles by topic, used instead of the {source} ones.",
    )


def storage_option(help: str, default: str | None = None) -> Callable[[F], F]:
    """-s/--storage: a storage plugin's id (a `default` is shown in the help)."""
    return click.option(
        "-s",
        "--storage",
        type=click.Choice(STORAGE_IDS),
        default=default,
        show_default=default is not None,
        help=help,
    )


def bag_argument(fn: F) -> F:
    """BAG_PATH and `-s/--storage`, as every verb reading a bag takes them."""
    fn = storage_option("Storage identifier (default: from the file extension).")(fn)
    decorated: F = click.argument("bag_path", type=click.Path())(fn)
    return decorated


def shared_options(verb: str, qos_source: str, *paused_flags: str) -> Callable[[F], F]:
    """The options record and play both have: -e/-x patterns, --exclude-topics, the QoS
    override file, --start-paused (also under `paused_flags`) and --disable-keyboard-controls
    (`verb`: 'record'/'play')."""

    def decorate(fn: F) -> F:
        for option in reversed(
            [
                click.option(
                    "-e",
                    "--regex",
                    help=f"{verb.title()} only topics matching the regular expression.",
                ),
                click.option(
                    "-x", "--exclude-regex", help="Exclude topics matching the regular expression."
                ),
                click.option(
                    "--exclude-topics",
                    cls=ManyValues,
                    metavar="TOPIC...",
                    help=f"List of topics not to {verb}.",
                ),
                qos_overrides_option(qos_source),
                click.option(
                    *paused_flags,
                    "--start-paused",
                    is_flag=True,
                    help="Start paused (SPACE resumes).",
                ),
                click.option(
                    "--disable-keyboard-controls", is_flag=True, help="Ignore the keyboard."
                ),
            ]
        ):
            fn = option(fn)
        return fn

    return decorate


def check_patterns(*patterns: str | None) -> None:
    """Refuse, in ros2bag's words, a `--regex`/`--exclude-regex` that does not compile."""
    import re

    for pattern in patterns:
        if pattern:
            try:
                re.compile(pattern)
            except re.error as e:
                raise bag_error(f"Invalid regular expression '{pattern}': {e}") from None


def bag_error(message: str) -> CliError:
    """ros2bag's error line."""
    return CliError(f"[ERROR] [ros2bag]: {message}")


def warn(message: str) -> None:
    click.echo(f"[WARN] [ros2bag]: {message}", err=True)


def qos_overrides(path: str | None) -> dict[str, QoSProfile]:
    """The `--qos-profile-overrides-path` file, read by the library (bag.qos)."""
    if path is None:
        return {}
    from ros2lite.bag.errors import BagError
    from ros2lite.bag.qos import read_qos_overrides

    try:
        return read_qos_overrides(path)
    except BagError as e:
        raise bag_error(str(e)) from None


def parse_remaps(rules: Iterable[str]) -> dict[str, str]:
    """`-m/--remap OLD:=NEW...` as a mapping (ros2bag's error for a malformed rule)."""
    remaps = {}
    for rule in rules:
        old, sep, new = rule.partition(":=")
        if not sep or not old or not new:
            raise bag_error(f"Remapping '{rule}' is not OLD:=NEW")
        remaps[old] = new
    return remaps


def bag_names(node: Node, names: Iterable[str]) -> list[str]:
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


def resolve_remaps(node: Node, remaps: dict[str, str]) -> dict[str, str]:
    """Remappings with every form the old name may have in the bag and the new one resolved."""
    return {
        old: node.resolve_topic_name(new)
        for given, new in remaps.items()
        for old in bag_names(node, [given])
    }


def existing_bag(bag_path: str) -> Path:
    """The bag path, refused in ros2bag's words when nothing is there."""
    path = Path(bag_path)
    if not path.exists():
        raise bag_error(f"Bag path '{bag_path}' does not exist!")
    return path


@contextlib.contextmanager
def bag_player(
    bag_path: str,
    storage: str | None,
    node_name: str,
    remap: Iterable[str],
    qos_profile_overrides_path: str | None,
    options: Callable[[Node], PlayOptions],
    patterns: Iterable[str | None] = (),
) -> Iterator[tuple[Player, RcutilsLogger]]:
    """The Player of `bag play` and `bag burst` on this run's connection, with its logger:
    the bag, remappings and QoS override file checked first (ros2bag's error lines), then the
    bag opened and the player node made. `patterns` (-e/-x) are checked after the bag path.
    `options(node)` gives the verb's own play options
    (names resolve against the node); remappings and QoS overrides are filled in here."""
    import dataclasses

    from ros2lite.bag.errors import BagError
    from ros2lite.bag.player import Player
    from ros2lite.bag.reader import Reader
    from ros2lite.logging import get_logger

    from ..common import connect

    existing_bag(bag_path)
    check_patterns(*patterns)
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
            play_options = dataclasses.replace(
                options(node), remap=resolve_remaps(node, remaps), qos_overrides=overrides
            )
            player = Player(
                node, reader, play_options, log=lambda m: log.info(m), warn=lambda m: log.warn(m)
            )
        except (BagError, ValueError) as e:
            raise bag_error(str(e)) from None
        yield player, log


TIME_HELP = (
    "seconds from the bag's start (90), a duration from the start (1:30, 1:02:03.5), or an "
    "absolute time (seconds or nanoseconds since the epoch, or 2024-05-01T12:00:00, UTC)"
)


def run_cut(
    bag_path: str,
    output: str,
    *,
    start: str | None = None,
    end: str | None = None,
    topics: list[str] | None = None,
    exclude: list[str] | None = None,
) -> None:
    """What `bag cut` and `bag filter` both do: parse the times against the bag, cut, say
    what the new bag holds."""
    from ros2lite.bag import Reader
    from ros2lite.bag.cut import cut, parse_time
    from ros2lite.bag.errors import BagError

    try:
        with Reader(bag_path) as reader:
            origin = reader.start_time if reader.message_count else 0
        begin = None if start is None else parse_time(start, origin)
        finish = None if end is None else parse_time(end, origin)
        result = cut(bag_path, output, start=begin, end=finish, topics=topics, exclude=exclude)
    except BagError as e:
        raise bag_error(str(e)) from None
    for line in result.problems:
        warn(line)
    m = result.metadata
    how = (
        f"{result.chunks_copied} chunks copied, {result.chunks_rewritten} re-encoded"
        if result.spliced
        else "rewritten message by message"
    )
    click.echo(
        f"Wrote {m.message_count} messages on {len(m.topics_with_message_count)} topics "
        f"to '{output}' ({how})"
    )
