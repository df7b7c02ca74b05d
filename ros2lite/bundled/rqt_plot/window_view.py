"""rqt_plot in a tkinter window: a tool bar (pause, autoscale, the time window in seconds,
clear) over a canvas where the library's chart layout (ros2lite.monitor.chart) is painted —
the same shapes a `topic plot --png` picture has."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

from ros2lite.bundled.display import open_window
from ros2lite.monitor.chart import Chart, layout, ranges
from ros2lite.monitor.plot import Plot, to_chart

WIDTH, HEIGHT = 620, 420  # the canvas at first (it follows the window's size)
_ANCHORS = {'start': 'w', 'middle': 'center', 'end': 'e'}


def _hex(colour: tuple[int, int, int]) -> str:
    return '#{:02x}{:02x}{:02x}'.format(*colour)


class PlotWindow:
    """A window titled `rqt_plot` (or `title`); `run` until closed, `ok()` turns False or
    Ctrl-C. `window` None shows all samples (a bag), else the last `window` seconds."""

    def __init__(
        self,
        plot: Plot,
        window: float | None,
        title: str = 'rqt_plot',
        add: Callable[[str], str | None] | None = None,
    ) -> None:
        import tkinter

        self.plot = plot
        self.add = add  # plots one more series (None: this window's series are fixed)
        self.problem = ''  # why the last series typed in could not be added
        self.window = window
        self.paused = False
        self.closed = False
        self.y_range: tuple[float, float] | None = None  # fixed while autoscale is off
        self.root = root = open_window('rqt_plot', title)
        root.protocol('WM_DELETE_WINDOW', self._close)
        bar = tkinter.Frame(root)
        bar.pack(side='top', fill='x')
        self.pause = tkinter.Button(bar, text='Pause', command=self._toggle_pause)
        self.pause.pack(side='left')
        self.autoscale = tkinter.BooleanVar(root, True)
        tkinter.Checkbutton(
            bar, text='Autoscale', variable=self.autoscale, command=self._autoscale_changed
        ).pack(side='left')
        if window is not None:
            tkinter.Label(bar, text='  Window (s)').pack(side='left')
            self.span = tkinter.StringVar(root, f'{window:g}')
            tkinter.Spinbox(
                bar, from_=1, to=3600, increment=1, width=6, textvariable=self.span
            ).pack(side='left')
        tkinter.Button(bar, text='Clear', command=plot.clear).pack(side='left')
        if add is not None:  # rqt_plot's topic row, above the buttons
            row = tkinter.Frame(root)
            row.pack(side='top', fill='x', before=bar)
            tkinter.Label(row, text='Topic').pack(side='left')
            self.topic = tkinter.StringVar(root, '')
            entry = tkinter.Entry(row, textvariable=self.topic)
            entry.pack(side='left', fill='x', expand=True)
            entry.bind('<Return>', lambda _e: self._add())
            tkinter.Button(row, text='+', command=self._add).pack(side='left')
        self.status = tkinter.Label(root, anchor='w')
        self.status.pack(side='bottom', fill='x')
        self.canvas = tkinter.Canvas(
            root, width=WIDTH, height=HEIGHT, background='white', highlightthickness=0
        )
        self.canvas.pack(side='top', fill='both', expand=True)

    def _add(self) -> None:
        assert self.add is not None
        problem = self.add(self.topic.get())
        self.problem = problem or ''
        if problem is None:
            self.topic.set('')

    def _close(self) -> None:
        self.closed = True

    def _toggle_pause(self) -> None:
        self.paused = not self.paused
        self.pause.configure(text='Resume' if self.paused else 'Pause')

    def _autoscale_changed(self) -> None:
        # turning it off keeps the y range the lines have now
        self.y_range = None if self.autoscale.get() else ranges(self.chart())[1]

    def _span(self) -> float | None:
        if self.window is None:
            return None
        try:
            value = float(self.span.get())
        except ValueError:
            return self.window
        if value > 0:
            self.window = value
            self.plot.window = value  # what the series keep follows what is shown
        return self.window

    def chart(self) -> Chart:
        return to_chart(self.plot, window=self._span(), y_range=self.y_range)

    def draw(self) -> None:
        """Paint the chart as it is now over the whole canvas."""
        canvas = self.canvas
        width = max(canvas.winfo_width(), 64) if canvas.winfo_width() > 1 else WIDTH
        height = max(canvas.winfo_height(), 64) if canvas.winfo_height() > 1 else HEIGHT
        canvas.delete('all')
        for s in layout(self.chart(), width, height).shapes:
            if s.kind == 'rect':
                (ax, ay), (bx, by) = s.points
                canvas.create_rectangle(
                    ax,
                    ay,
                    bx,
                    by,
                    fill=_hex(s.colour),
                    outline=_hex(s.outline) if s.outline else '',
                )
            elif s.kind == 'line':
                flat = [v for point in s.points for v in point]
                canvas.create_line(*flat, fill=_hex(s.colour), width=s.width)
            else:
                x, y = s.points[0]
                anchor: Any = _ANCHORS[s.anchor]
                canvas.create_text(x, y, text=s.text, fill=_hex(s.colour), anchor=anchor)
        state = 'PAUSED · ' if self.paused else ''
        problem = f' · {self.problem}' if self.problem else ''
        self.status.configure(text=f'{state}{self.plot.messages} messages{problem}')

    def run(self, ok: Callable[[], bool], period: float = 0.1) -> None:
        """Redraw every `period` s (unless paused) until closed or not `ok()`."""
        drawn = 0.0
        try:
            while not self.closed and ok():
                now = time.monotonic()
                if not self.paused and now - drawn >= period:
                    drawn = now
                    self.draw()
                self.root.update()
                time.sleep(0.02)
        finally:
            self.root.destroy()
