"""rqt_plot on the terminal: the chart in braille filling the screen, the newest value and
rate of each series in the legend, and keys to pause, rescale and change the time window."""

from __future__ import annotations

import sys
import time
from collections.abc import Callable

from ros2lite.bundled.display import DisplayError
from ros2lite.bundled.terminal import LivePicture, terminal_size
from ros2lite.monitor.chart import braille, ranges
from ros2lite.monitor.plot import Plot, to_chart

KEYS = 'p pause · a autoscale · +/- time window · c clear · q quit'


class PlotTerminal:
    """The plot on the terminal; `run` until `q`, Ctrl-C or `ok()` turns False."""

    def __init__(self, plot: Plot, window: float) -> None:
        if not sys.stdout.isatty():
            raise DisplayError('cannot draw on the terminal: standard output is not a terminal')
        self.plot = plot
        self.window = window
        self.paused = False
        self.y_range: tuple[float, float] | None = None  # fixed while autoscale is off

    def picture(self, width: int, height: int) -> str:
        """The screen: chart, and a status line with the keys."""
        chart = to_chart(self.plot, window=self.window, y_range=self.y_range)
        flags = [f'window {self.window:g} s']
        if self.y_range is not None:
            flags.append('autoscale off')
        if self.paused:
            flags.append('PAUSED')
        chart.status = f'rqt_plot  {" · ".join(flags)}  ({KEYS})'
        return braille(chart, width, height)

    def key(self, key: str) -> bool:
        """Act on one key; False when it asks to quit."""
        if key == 'q':
            return False
        if key in ('p', ' '):
            self.paused = not self.paused
        elif key == 'a':
            chart = to_chart(self.plot, window=self.window)
            self.y_range = ranges(chart)[1] if self.y_range is None else None
        elif key in ('+', '='):
            self.window = min(self.window * 2, 3600.0)
        elif key == '-':
            self.window = max(self.window / 2, 0.5)
        if key in ('+', '=', '-'):
            self.plot.window = self.window  # what the series keep follows what is shown
        elif key == 'c':
            self.plot.clear()
        return True

    def run(self, ok: Callable[[], bool], period: float) -> None:
        """Redraw every `period` s unless paused; read keys meanwhile."""
        from ros2lite.util.keyboard import Keyboard

        keys = True  # until the input ends (then the plot is only shown)
        drawn = 0.0
        with LivePicture(sys.stdout) as live, Keyboard() as keyboard:
            while ok():
                now = time.monotonic()
                if now - drawn >= period:
                    drawn = now
                    if not self.paused:
                        width, height = terminal_size(sys.stdout)
                        # one line short of the screen, so the picture never scrolls it
                        live.show(self.picture(width, height - 1))
                key = None
                if keys:
                    try:
                        key = keyboard.read(period / 2)
                    except EOFError:
                        keys = False
                else:
                    time.sleep(period / 2)
                if key is not None:
                    if not self.key(key):
                        return
                    width, height = terminal_size(sys.stdout)
                    live.show(self.picture(width, height - 1))
