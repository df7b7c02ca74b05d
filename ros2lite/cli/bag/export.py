"""`bag export`: one topic of a bag as CSV, JSON lines, Parquet, or PNG frames."""

from __future__ import annotations

import click

from ..errors import CliError
from ..parsing import command
from .options import TIME_HELP, bag_error

_SUFFIXES = {".csv": "csv", ".jsonl": "jsonl", ".ndjson": "jsonl", ".parquet": "parquet"}


@command("export")
@click.argument("bag_path", type=click.Path())
@click.argument("topic")
@click.option("--csv", "fmt", flag_value="csv", help="Rows as `topic echo --csv` prints them.")
@click.option("--jsonl", "fmt", flag_value="jsonl", help="One JSON object per message.")
@click.option("--parquet", "fmt", flag_value="parquet", help="A Parquet table (needs pyarrow).")
@click.option("--png", "fmt", flag_value="png", help="Image frames as PNG files in a folder.")
@click.option(
    "-o",
    "--output",
    required=True,
    help="The file to write (for --png, a folder). The format follows its suffix when no "
    "format option is given; an image topic goes to PNG files.",
)
@click.option("--start", metavar="T", help=f"First time exported: {TIME_HELP}.")
@click.option("--end", metavar="T", help="Last time exported (included).")
@click.option(
    "-i",
    "--include-message-info",
    is_flag=True,
    help="Add times: CSV gets topic echo -i's four columns first, JSON a time envelope "
    "(Parquet always has log_time and publish_time).",
)
@click.option("--no-arr", is_flag=True, help="Don't write array fields of messages")
@click.option("--no-str", is_flag=True, help="Don't write string fields of messages")
def cli(
    bag_path: str,
    topic: str,
    fmt: str | None,
    output: str,
    start: str | None,
    end: str | None,
    include_message_info: bool,
    no_arr: bool,
    no_str: bool,
) -> None:
    """Export one topic of a bag to CSV, JSON lines, Parquet or PNG files."""
    from pathlib import Path

    from ros2lite.bag import Reader
    from ros2lite.bag.cut import parse_time
    from ros2lite.bag.errors import BagError
    from ros2lite.bag.export import IMAGE_TYPES, ExportOptions, export

    try:
        with Reader(bag_path) as reader:
            origin = reader.start_time if reader.message_count else 0
            meta = reader.topic(topic) or reader.topic("/" + topic)
            image = meta is not None and meta.type in IMAGE_TYPES
        if fmt is None:
            fmt = _SUFFIXES.get(Path(output).suffix.lower()) or ("png" if image else None)
            if fmt is None:
                raise CliError(
                    "Give --csv, --jsonl, --parquet or --png (or an output ending in .csv, "
                    ".jsonl or .parquet)"
                )
        options = ExportOptions(
            start=None if start is None else parse_time(start, origin),
            end=None if end is None else parse_time(end, origin),
            include_info=include_message_info,
            no_arr=no_arr,
            no_str=no_str,
        )
        n = export(bag_path, topic, fmt, output, options)
    except BagError as e:
        raise bag_error(str(e)) from None
    click.echo(f"Exported {n} messages of '{topic}' to '{output}' ({fmt})")
