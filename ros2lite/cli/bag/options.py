"""What the bag verbs share: options of record and play, ros2bag's error lines, QoS overrides."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any, TypeVar

import click

from ..errors import CliError

if TYPE_CHECKING:
    from ros2lite.qos import QoSProfile

F = TypeVar("F", bound=Callable[..., Any])


def bag_argument(fn: F) -> F:
    """BAG_PATH and `-s/--storage`, as every verb reading a bag takes them."""
    fn = click.option(
        "-s",
        "--storage",
        type=click.Choice(["mcap", "sqlite3"]),
        help="Storage identifier (default: from the file extension).",
    )(fn)
    decorated: F = click.argument("bag_path", type=click.Path())(fn)
    return decorated


def shared_options(verb: str, qos_source: str, *paused_flags: str) -> Callable[[F], F]:
    """The options record and play both have: -e/-x patterns, --exclude-topics, the QoS
    override file, --start-paused (also under `paused_flags`) and --disable-keyboard-controls
    (`verb`: 'record'/'play')."""
    from ..common import ManyValues

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
                click.option(
                    "--qos-profile-overrides-path",
                    type=click.Path(dir_okay=False),
                    help=f"YAML file of QoS profiles by topic, used instead of the {qos_source} "
                    "ones.",
                ),
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
