"""A plot of a whole bag (`ros2lite bag plot`): the named series over every message of their
topics, x the log time from the first plotted message, or each message's header stamp.

The series, field paths and pictures are the live plots' own (ros2lite.monitor.plot); this
module only walks the bag.
"""

from __future__ import annotations

from collections.abc import Sequence

from ros2lite.bag.reader import Reader
from ros2lite.monitor.plot import (
    Plot,
    PlotError,
    SeriesSpec,
    expand_specs,
    split_last_fields,
    split_topic,
)

__all__ = ['bag_plot']


def bag_plot(
    path: str,
    texts: Sequence[str],
    *,
    mode: str = 'time',
    header_stamp: bool = False,
    rows: list[list[str]] | None = None,
    capacity: int = 2_000_000,
    storage_id: str | None = None,
) -> Plot:
    """The plot of `texts` (``/turtle1/pose/x``…) over the bag at `path`; PlotError when a
    text names no topic of the bag or no number in its messages. Each series keeps its last
    `capacity` samples (2 million: about 130 MB), so a huge bag cannot take all memory."""
    with Reader(path, storage_id) as bag:
        names = [t.name for t in bag.topics]
        specs = [s for text in texts for s in _specs(text, names)]
        plot = Plot(
            specs,
            mode=mode,
            capacity=capacity,
            window=None,
            header_stamp=header_stamp,
            rows=rows,
            live=False,
        )
        checked: set[str] = set()
        first: int | None = None
        for topic, msg, log_time in bag.messages(plot.topics):
            if first is None:
                first = log_time  # times from here: nanoseconds since 1970 overflow a float's
            if topic not in checked:
                if isinstance(msg, bytes):
                    raise PlotError(f"'{topic}': its type cannot be decoded here")
                plot.check(topic, type(msg))
                checked.add(topic)
            plot.feed(topic, msg, (log_time - first) * 1e-9)
    return plot


def _specs(text: str, names: list[str]) -> list[SeriesSpec]:
    if split_topic(split_last_fields(text)[0], names) is None:
        raise PlotError(
            f"no topic of the bag matches '{text}' (its topics: {', '.join(sorted(names))})"
        )
    return expand_specs(text, names)
