"""`bag filter`: a new bag holding some of a bag's topics (and, optionally, a time range)."""

from __future__ import annotations

import click

from ..errors import CliError
from ..parsing import ManyValues, command
from .options import TIME_HELP, run_cut


@command("filter")
@click.argument("bag_path", type=click.Path())
@click.option("-o", "--output", required=True, help="The new bag's directory.")
@click.option("--topics", cls=ManyValues, metavar="TOPIC...", help="Keep only these topics.")
@click.option("--exclude", cls=ManyValues, metavar="TOPIC...", help="Leave these topics out.")
@click.option("--start", metavar="T", help=f"First time kept: {TIME_HELP}.")
@click.option("--end", metavar="T", help="Last time kept (included).")
def cli(
    bag_path: str,
    output: str,
    topics: tuple[str, ...],
    exclude: tuple[str, ...],
    start: str | None,
    end: str | None,
) -> None:
    """Write some topics of a bag into a new bag."""
    if not topics and not exclude:
        raise CliError("[ERROR] [ros2bag]: give --topics, --exclude or both")
    run_cut(
        bag_path,
        output,
        start=start,
        end=end,
        topics=list(topics) if topics else None,
        exclude=list(exclude) if exclude else None,
    )
