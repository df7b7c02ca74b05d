"""`bag cut`: a new bag holding a bag's messages from one time to another."""

from __future__ import annotations

import click

from ..parsing import command
from .options import TIME_HELP, run_cut


@command("cut")
@click.argument("bag_path", type=click.Path())
@click.option("-o", "--output", required=True, help="The new bag's directory.")
@click.option("--start", metavar="T", help=f"First time kept: {TIME_HELP}. Default: the start.")
@click.option("--end", metavar="T", help="Last time kept (included). Default: the end.")
def cli(bag_path: str, output: str, start: str | None, end: str | None) -> None:
    """Write the messages of a bag between two times into a new bag."""
    run_cut(bag_path, output, start=start, end=end)
