"""What the bag verbs share: argparse-style `nargs='+'` options, errors, QoS overrides."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import click

from ..errors import CliError

if TYPE_CHECKING:
    from ros2lite.qos import QoSProfile


class ManyValues(click.Option):
    """An option that takes every following word up to the next option, as argparse's
    `nargs='+'` does (`--topics /a /b -o out`). It may also be repeated."""

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        kwargs.setdefault("multiple", True)
        super().__init__(*args, **kwargs)

    def add_to_parser(self, parser: Any, ctx: click.Context) -> None:
        super().add_to_parser(parser, ctx)
        for name in self.opts:
            opt = parser._long_opt.get(name) or parser._short_opt.get(name)
            if opt is None:
                continue
            previous = opt.process

            def process(value: Any, state: Any, previous: Any = previous) -> None:
                values = [value]
                while state.rargs and not state.rargs[0].startswith("-"):
                    values.append(state.rargs.pop(0))
                for v in values:
                    previous(v, state)

            opt.process = process


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
