"""`bag convert`: rewrite bags into new ones (merge, filter by topic or time, re-split,
compress), as described by an output-options YAML file (rosbag2's `output_bags:` list)."""

from __future__ import annotations

import click

from ..parsing import ValueGroups, command
from .options import STORAGE_IDS, bag_error


@command("convert")
@click.option(
    "-i",
    "--input",
    "inputs",
    cls=ValueGroups,
    required=True,
    metavar="URI [STORAGE_ID]",
    help="An input bag and, optionally, its storage id. May be given more than once.",
)
@click.option(
    "-o",
    "--output-options",
    required=True,
    type=click.Path(dir_okay=False),
    help="YAML file with the options of each output bag ('output_bags:' list).",
)
def cli(inputs: tuple[tuple[str, ...], ...], output_options: str) -> None:
    """Given an input bag, write out a new bag with different settings."""
    from ros2lite.bag.convert import convert, read_output_options
    from ros2lite.bag.errors import BagError

    sources: list[tuple[str, str | None]] = []
    for given in inputs:
        if len(given) > 2:
            raise bag_error(f"--input expects 1 or 2 arguments, {len(given)} provided")
        storage = given[1] if len(given) == 2 else None
        if storage is not None and storage not in STORAGE_IDS:
            choices = ", ".join(STORAGE_IDS)
            raise bag_error(f"Unknown storage id '{storage}' (choose from {choices})")
        sources.append((given[0], storage))
    try:
        convert(sources, read_output_options(output_options))
    except BagError as e:
        raise bag_error(str(e)) from None
