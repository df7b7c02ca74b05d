"""`bag plot`: numeric fields over a whole bag (time on x: the log time, or each message's
header stamp), drawn in the terminal or a window, or written as PNG/SVG or CSV rows."""

from __future__ import annotations

import click

from ..common import plot_request
from ..errors import CliError
from ..options import plot_options
from ..parsing import command
from ..render import print_chart, write_plot
from .options import bag_argument, bag_error, existing_bag, warn


@command("plot")
@bag_argument
@click.argument("series", nargs=-1, required=True, metavar="TOPIC/FIELD...")
@plot_options(live=False)
@click.option(
    "--display",
    type=click.Choice(["terminal", "window"]),
    default="terminal",
    show_default=True,
    help="Where to draw when no file is asked for: braille text, or a window (as rqt_plot's)",
)
def cli(
    bag_path: str,
    storage: str | None,
    series: tuple[str, ...],
    xy: bool,
    snapshot: bool,
    header_stamp: bool,
    png_path: str | None,
    svg_path: str | None,
    csv_out: bool,
    size: tuple[int, int],
    display: str,
) -> None:
    """Plot numeric fields of a bag's messages (TOPIC/FIELD as rqt_plot takes them)."""
    from ros2lite.bag.errors import BagError
    from ros2lite.bag.plot import bag_plot
    from ros2lite.monitor.plot import PlotError

    texts, pictures = plot_request(series, xy, snapshot, (png_path, svg_path), csv_out)
    existing_bag(bag_path)
    rows: list[list[str]] | None = [] if csv_out else None
    try:
        plot = bag_plot(
            bag_path,
            texts,
            mode="xy" if xy else "snapshot" if snapshot else "time",
            header_stamp=header_stamp,
            rows=rows,
            storage_id=storage,
        )
    except PlotError as e:
        raise CliError(str(e)) from None
    except BagError as e:
        raise bag_error(str(e)) from None
    cut = [s.label for s in plot.series if s.count > len(s.points()[0]) and plot.mode == "time"]
    if cut:
        warn(f"only the last samples of {', '.join(cut)} are plotted (a series keeps 2 million)")
    if plot.messages == 0:
        click.echo(f"[WARN] [ros2bag]: no messages of {', '.join(plot.topics)}", err=True)
    if rows is not None:
        click.echo(",".join(plot.csv_header()))
        for row in rows:
            click.echo(",".join(row))
    elif pictures:
        write_plot(plot, pictures, size)
    elif display == "window":
        from ros2lite.bundled.display import DisplayError
        from ros2lite.bundled.rqt_plot.window_view import PlotWindow

        try:
            PlotWindow(plot, window=None, title=f"bag plot: {bag_path}").run(lambda: True)
        except DisplayError as e:
            raise CliError(str(e)) from None
    else:
        print_chart(plot, None)
