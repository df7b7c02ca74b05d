"""Plotting numbers out of messages: field paths, bounded series, and feeding them from a live
topic or a whole bag.

One room for what `topic plot`, `bag plot` and the bundled `rqt_plot` share. A series is named
as rqt_plot names it, topic and field path in one: ``/turtle1/pose/x``, ``/scan/ranges[0]``,
``/odom/pose/pose/position/x``; the topic is the longest known topic the text starts with, the
rest is the path (``/`` between fields, ``[i]`` for an element, ``.`` accepted as ``/`` is).
``/turtle1/pose/x:y`` (or ``,y``) is two series of one topic. Series keep their newest samples
in ring buffers bounded both by count and by a time window, so a 1 kHz topic watched for hours
holds a fixed amount of memory.
"""

from __future__ import annotations

import bisect
import threading
import time
from collections import deque
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ros2lite.interfaces import CdrError, deserialize, get_interface
from ros2lite.interfaces.convert import value_to_csv
from ros2lite.monitor.chart import PALETTE, Chart, Line, png, svg
from ros2lite.monitor.fields import (
    FieldPath,
    PlotError,
    SeriesSpec,
    expand_specs,
    field_types,
    numeric,
    split_last_fields,
    split_topic,
)
from ros2lite.monitor.subscription import MonitoredSubscription
from ros2lite.util.files import replace_file

if TYPE_CHECKING:
    from ros2lite.monitor.topic import TopicMonitor
    from ros2lite.qos import QoSProfile
    from ros2lite.subscription import Subscription

__all__ = [
    'DEFAULT_CAPACITY',
    'DEFAULT_WINDOW',
    'FieldPath',
    'Plot',
    'PlotError',
    'Series',
    'SeriesSpec',
    'Snapshot',
    'expand_specs',
    'numeric',
    'resolve_specs',
    'save_picture',
    'split_last_fields',
    'split_topic',
    'subscribe',
    'to_chart',
]

DEFAULT_WINDOW = 10.0  # s of samples shown by a live plot (rqt_plot's scrolling window)
DEFAULT_CAPACITY = 100_000  # samples kept per series: 100 s of a 1 kHz topic
RATE_SPAN = 2.0  # s over which a series' rate is measured


class Series:
    """The newest (time, value) samples of one spec, kept under a lock (fed by the executor
    thread, read by the drawing one), bounded by `capacity` samples and `window` seconds."""

    def __init__(self, spec: SeriesSpec, capacity: int = DEFAULT_CAPACITY) -> None:
        self.spec = spec
        self.label = spec.label
        self.times: deque[float] = deque(maxlen=capacity)
        self.values: deque[float] = deque(maxlen=capacity)
        self.count = 0  # samples ever added
        self.ordered = True  # no sample's time was before the one before it
        self._arrived = 0.0  # monotonic time of the newest sample
        self.lock = threading.Lock()

    def add(self, t: float, value: float, arrival: float | None = None) -> None:
        with self.lock:
            if self.times and t < self.times[-1]:
                self.ordered = False
            self.times.append(t)
            self.values.append(value)
            self._arrived = time.monotonic() if arrival is None else arrival
            self.count += 1

    def trim(self, before: float) -> None:
        """Forget samples older than `before` (the time window's start)."""
        with self.lock:
            while self.times and self.times[0] < before:
                self.times.popleft()
                self.values.popleft()

    def clear(self) -> None:
        with self.lock:
            self.times.clear()
            self.values.clear()
            self.ordered = True

    def points(self, start: float | None = None) -> tuple[list[float], list[float]]:
        """Copies of the samples (from time `start` on)."""
        with self.lock:
            ts, vs = list(self.times), list(self.values)
        if start is not None and ts and ts[0] < start:
            i = bisect.bisect_left(ts, start)
            ts, vs = ts[i:], vs[i:]
        return ts, vs

    def last(self) -> float | None:
        with self.lock:
            return self.values[-1] if self.values else None

    def rate(self, live: bool = True) -> float:
        """Samples per second over the newest RATE_SPAN s of sample times; 0 when `live` and
        nothing arrived for that long."""
        with self.lock:
            if not self.times or (live and time.monotonic() - self._arrived > RATE_SPAN):
                return 0.0
            end = self.times[-1]
            n = 0
            first = end
            for t in reversed(self.times):
                if t < end - RATE_SPAN:
                    break
                n += 1
                first = t
        return 0.0 if n < 2 or end <= first else (n - 1) / (end - first)


class Snapshot:
    """The newest value of an array field (a LaserScan's ranges), as a profile."""

    def __init__(self, spec: SeriesSpec) -> None:
        self.spec = spec
        self.label = spec.label
        self.values: list[float] = []
        self.count = 0
        self._times: deque[float] = deque(maxlen=10_000)
        self._arrived = 0.0
        self.lock = threading.Lock()

    def add(self, t: float, values: Sequence[object], arrival: float | None = None) -> None:
        data = [numeric(v) for v in values]
        with self.lock:
            self.values = data
            self.count += 1
            self._times.append(t)
            self._arrived = time.monotonic() if arrival is None else arrival

    def points(self, start: float | None = None) -> tuple[list[float], list[float]]:
        with self.lock:
            ys = list(self.values)
        return [float(i) for i in range(len(ys))], ys

    def last(self) -> float | None:
        with self.lock:
            return self.values[-1] if self.values else None

    def rate(self, live: bool = True) -> float:
        """Arrays per second over the newest RATE_SPAN s (their times, as Series.rate)."""
        with self.lock:
            times = self._times
            if not times or (live and time.monotonic() - self._arrived > RATE_SPAN):
                return 0.0
            while times and times[0] < times[-1] - RATE_SPAN:
                times.popleft()
            n = len(times)
            return 0.0 if n < 2 else (n - 1) / max(times[-1] - times[0], 1e-9)

    def clear(self) -> None:
        with self.lock:
            self.values = []


@dataclass
class Plot:
    """Everything one plot shows, fed message by message.

    mode 'time': each spec is a line over time; 'xy': the two specs are x and y of one path
    (`xy` samples: the x series' values against the y series'); 'snapshot': each spec is an
    array drawn against its indices. `rows` (when a list) gets a CSV row per message: the time
    (s from the first sample), then each series' value as `topic echo --csv` writes it (empty
    for the other topics' series); in snapshot mode the time, the label, the array.
    """

    specs: list[SeriesSpec]
    mode: str = 'time'
    capacity: int = DEFAULT_CAPACITY
    window: float | None = DEFAULT_WINDOW  # s; None keeps everything (a bag)
    header_stamp: bool = False
    rows: list[list[str]] | None = None
    on_sample: Callable[[], object] | None = None
    series: list[Series | Snapshot] = field(init=False)
    start: float | None = None  # the time of the first sample (x = 0)
    latest: float = 0.0
    messages: int = 0  # messages fed
    live: bool = True  # fed as messages arrive (a bag's are not: its rates need no decay)
    limit: int | None = None  # messages taken at most (later ones are ignored)

    def __post_init__(self) -> None:
        if self.mode not in ('time', 'xy', 'snapshot'):
            raise ValueError(f'unknown plot mode {self.mode!r}')
        if self.mode == 'xy' and len(self.specs) != 2:
            raise PlotError('an x-y plot takes two values of one topic (as /odom/…/x,y)')
        if self.mode == 'xy' and self.specs[0].topic != self.specs[1].topic:
            raise PlotError('the x and y of an x-y plot must come from one topic')
        if self.mode == 'snapshot':
            self.series = [Snapshot(s) for s in self.specs]
        else:
            self.series = [Series(s, self.capacity) for s in self.specs]
        self._lock = threading.Lock()
        self._feeding = threading.Lock()  # one message at a time (receive threads, a bag)
        self._xy: deque[tuple[float, float]] = deque(maxlen=self.capacity)
        self._by_topic: dict[str, list[int]] = {}
        for i, spec in enumerate(self.specs):
            self._by_topic.setdefault(spec.topic, []).append(i)

    def add(self, specs: Sequence[SeriesSpec]) -> list[SeriesSpec]:
        """Plot more series of a time plot while it runs (rqt_plot's topic box); returns the
        ones it did not have yet."""
        if self.mode != 'time':
            raise PlotError('series are added to a plot over time only')
        fresh = [s for s in specs if s not in self.specs]
        with self._feeding:
            for spec in fresh:
                self.specs.append(spec)
                self.series.append(Series(spec, self.capacity))
                self._by_topic.setdefault(spec.topic, []).append(len(self.specs) - 1)
        return fresh

    @property
    def topics(self) -> list[str]:
        """The topics to subscribe to, in the order first named."""
        return list(self._by_topic)

    def check(self, topic: str, cls: type) -> None:
        """PlotError unless every path of `topic` names what this mode plots in `cls`."""
        want = 'array' if self.mode == 'snapshot' else 'number'
        for i in self._by_topic.get(topic, []):
            spec = self.specs[i]
            kind = spec.check(cls)
            if kind != want:
                if want == 'array':
                    raise PlotError(f"'{spec.label}' is one number; --snapshot plots arrays")
                raise PlotError(f"'{spec.label}' is an array; name an element ([0]) of it")
        if self.header_stamp and 'header' not in (field_types(cls) or {}):
            raise PlotError(f"'{topic}' has no header, so it has no header stamp to plot by")

    def feed(self, topic: str, msg: object, log_time: float) -> None:
        """Add the values of one message of `topic` received (or logged) at `log_time`
        (seconds); a value past an array's end is skipped."""
        with self._feeding:
            if self.limit is None or self.messages < self.limit:
                self._feed(topic, msg, log_time)

    def _feed(self, topic: str, msg: object, log_time: float) -> None:
        t = log_time
        if self.header_stamp:
            stamp = msg.header.stamp  # type: ignore[attr-defined]
            t = stamp.sec + stamp.nanosec * 1e-9
        with self._lock:
            if self.start is None:
                self.start = t
            self.latest = max(self.latest, t)
            self.messages += 1
        x = t - self.start
        now = time.monotonic()
        values: list[float | None] = []
        cells: dict[int, str] = {}
        for i in self._by_topic.get(topic, ()):
            try:
                raw = self.specs[i].path.get(msg)
            except IndexError:
                values.append(None)
                continue
            target = self.series[i]
            if isinstance(target, Snapshot):
                assert isinstance(raw, Sequence)  # checked an array of numbers by its spec
                target.add(x, raw, now)
                if self.rows is not None:
                    self.rows.append([f'{x:.6f}', target.label, *(value_to_csv(v) for v in raw)])
                values.append(None)
                continue
            value = numeric(raw)
            target.add(x, value, now)
            values.append(value)
            cells[i] = value_to_csv(raw)
        if self.rows is not None and cells:
            self.rows.append([f'{x:.6f}', *(cells.get(i, '') for i in range(len(self.specs)))])
        if self.mode == 'xy' and len(values) == 2 and None not in values:
            with self._lock:
                self._xy.append((values[0], values[1]))  # type: ignore[arg-type]
        if self.window is not None and self.mode == 'time' and self.messages % 64 == 0:
            # now and then: the window bounds what is kept, the draw cuts exactly
            for s in self.series:
                if isinstance(s, Series):
                    s.trim(self.latest - self.start - self.window)
        if self.on_sample is not None:
            self.on_sample()

    def xy_points(self) -> tuple[list[float], list[float]]:
        """The x-y path so far (newest `capacity` points)."""
        with self._lock:
            pairs = list(self._xy)
        return [p[0] for p in pairs], [p[1] for p in pairs]

    def csv_header(self) -> list[str]:
        """The column names of `rows`."""
        if self.mode == 'snapshot':
            return ['time', 'series', 'values']
        return ['time', *(s.label for s in self.specs)]

    def now(self) -> float:
        """The x of the newest sample (the right edge of a scrolling window)."""
        with self._lock:
            return 0.0 if self.start is None else self.latest - self.start

    def clear(self) -> None:
        for s in self.series:
            s.clear()
        with self._lock:
            self._xy.clear()


# -- live topics -------------------------------------------------------------------------------


def resolve_specs(
    texts: Sequence[str],
    topic_names: Callable[[], Iterable[str]],
    on_waiting: Callable[[str], object] | None = None,
    poll: float = 0.2,
    timeout: float | None = None,
) -> list[SeriesSpec]:
    """The series `texts` name, each split at the longest topic `topic_names()` knows; a text
    no topic fits yet is waited for (`on_waiting(text)` said once), PlotError after
    `timeout` s (None: wait as long as it takes). A malformed path fails at once."""
    specs: list[SeriesSpec] = []
    deadline = None if timeout is None else time.monotonic() + timeout
    for text in texts:
        head = split_last_fields(text)[0]
        FieldPath.parse(head)  # a typo is said now, not after waiting
        said = False
        while True:
            names = list(topic_names())
            if split_topic(head, names) is not None:
                specs += expand_specs(text, names)
                break
            if not said and on_waiting is not None:
                on_waiting(text)
            said = True
            if deadline is not None and time.monotonic() >= deadline:
                raise PlotError(f"no topic in the graph matches '{text}'")
            time.sleep(poll)
    return specs


def subscribe(
    plot: Plot,
    monitors: dict[str, TopicMonitor],
    types: dict[str, str],
    qos: Callable[[TopicMonitor], QoSProfile],
    topics: Sequence[str] | None = None,
) -> list[Subscription]:
    """Subscribe `plot` to each of its topics with the QoS `qos(monitor)` picks for it
    (matched to its publishers, so sensor-data topics plot). Each message is decoded and its
    values taken at its arrival time (or its header stamp) on the receive thread, as a tool's
    arrival hook: nothing is queued, so a fast topic is never thinned by a queue's depth and a
    1 kHz topic costs no executor wake-ups. `topics` (all of the plot's by default) are the
    ones to subscribe to now."""
    subs: list[Subscription] = []
    for topic in plot.topics if topics is None else topics:
        watch = monitors[topic]
        cls = get_interface(types[topic])
        plot.check(topic, cls)
        warned: list[bool] = []

        def arrived(
            cdr: bytes,
            _attachment: bytes,
            _received: int,
            topic: str = topic,
            cls: type = cls,
            warned: list[bool] = warned,
            watch: TopicMonitor = watch,
        ) -> None:
            try:
                msg = deserialize(cls, cdr)
            except CdrError as e:
                if not warned:
                    warned.append(True)
                    watch.node.get_logger().warn(
                        f"dropping samples on '{topic}' that are not a {cls.__name__}: {e}"
                    )
                return
            plot.feed(topic, msg, time.time())

        subs.append(
            MonitoredSubscription(
                watch.node, cls, watch.topic, None, qos(watch), on_payload=arrived
            )
        )
    return subs


# -- pictures ----------------------------------------------------------------------------------


def to_chart(
    plot: Plot,
    *,
    window: float | None = None,
    y_range: tuple[float, float] | None = None,
    readout: bool = True,
    x_label: str | None = None,
) -> Chart:
    """What `plot` shows now as a chart: a time plot scrolls over the last `window` s (all of
    it when None), an x-y plot is one path, a snapshot each array against its indices. The
    legend reads the newest value and the rate of each series when `readout`."""

    def note(s: Series | Snapshot) -> str:
        if not readout:
            return ''
        last = s.last()
        if last is None:
            return '(no data yet)'
        return f'= {last:.6g}  {s.rate(plot.live):.1f} Hz'

    if plot.mode == 'xy':
        xs, ys = plot.xy_points()
        x_spec, y_spec = plot.specs
        label = f'{y_spec.label} against {x_spec.path}'
        last = f'= ({xs[-1]:.6g}, {ys[-1]:.6g})' if xs and readout else ''
        lines = [Line(label, xs, ys, PALETTE[0], last)]
        return Chart(lines, y_range=y_range, x_label=x_label or str(x_spec.path))
    lines = []
    for i, s in enumerate(plot.series):
        start = None if window is None else plot.now() - window
        xs, ys = s.points(start)
        ordered = s.ordered if isinstance(s, Series) else True
        lines.append(Line(s.label, xs, ys, PALETTE[i % len(PALETTE)], note(s), ordered))
    if plot.mode == 'snapshot':
        return Chart(lines, y_range=y_range, x_label=x_label or 'index')
    x_range = None
    if window is not None:
        right = max(plot.now(), window)
        x_range = (right - window, right)
    return Chart(lines, x_range=x_range, y_range=y_range, x_label=x_label or 'time (s)')


PICTURE_FORMATS = ('png', 'svg')


def save_picture(chart: Chart, path: str, size: tuple[int, int] = (800, 480)) -> None:
    """Write `chart` to `path` as PNG or SVG (by the name's suffix), replacing the file
    whole and never through a symlink."""
    kind = path.rsplit('.', 1)[-1].lower() if '.' in path else ''
    if kind not in PICTURE_FORMATS:
        raise PlotError(f"'{path}': a picture is written as .png or .svg")
    data: bytes | str = png(chart, *size) if kind == 'png' else svg(chart, *size)
    replace_file(path, data, sync=False)
