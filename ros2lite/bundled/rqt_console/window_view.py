"""rqt_console in a tkinter window: a tool bar (pause, clear, least severity, node and text
filters), the table of messages with each row tinted by its severity, and a status line."""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from ros2lite.bundled.display import open_window
from ros2lite.bundled.rqt_console.model import (
    COLUMNS,
    SEVERITIES,
    TINTS,
    Console,
    cells,
    line,
    widths,
)

if TYPE_CHECKING:
    import tkinter

SHOWN_ROWS = 500  # the newest rows the table holds (the console keeps more)
TABLE_CHARACTERS = 120  # the table's width in characters of the fixed-width font


def _hex(colour: tuple[int, int, int]) -> str:
    return '#{:02x}{:02x}{:02x}'.format(*colour)


class ConsoleWindow:
    """A window titled `rqt_console`; `run` until closed, `ok()` turns False or Ctrl-C."""

    def __init__(self, console: Console) -> None:
        import tkinter

        self.console = console
        self.root = root = open_window('rqt_console', 'rqt_console')
        self.closed = False
        root.protocol('WM_DELETE_WINDOW', self._close)
        bar = tkinter.Frame(root)
        bar.pack(side='top', fill='x')
        self.pause = tkinter.Button(bar, text='Pause', command=self._toggle_pause)
        self.pause.pack(side='left')
        tkinter.Button(bar, text='Clear', command=console.clear).pack(side='left')
        filters = console.filters
        tkinter.Label(bar, text='  Severity ≥').pack(side='left')
        self.severity = tkinter.StringVar(root, filters.severity)
        tkinter.OptionMenu(bar, self.severity, *SEVERITIES).pack(side='left')
        self.severity.trace_add(
            'write', lambda *_: console.set_filters(severity=self.severity.get())
        )
        self.node = self._entry(bar, 'Node', filters.node, 'node')
        self.text = self._entry(bar, 'Text', filters.text, 'text')
        self.status = tkinter.Label(root, anchor='w')
        self.status.pack(side='bottom', fill='x')
        self.header = tkinter.Label(root, anchor='w', font='TkFixedFont', background='#e0e0e0')
        self.header.pack(side='top', fill='x')
        body = tkinter.Frame(root)
        body.pack(side='top', fill='both', expand=True)
        scroll = tkinter.Scrollbar(body)
        scroll.pack(side='right', fill='y')
        self.table = tkinter.Text(
            body,
            font='TkFixedFont',
            wrap='none',
            width=TABLE_CHARACTERS,
            height=24,
            background='white',
            yscrollcommand=scroll.set,
        )
        self.table.pack(side='left', fill='both', expand=True)
        scroll.configure(command=self.table.yview)
        for name in SEVERITIES:
            self.table.tag_configure(name, background=_hex(TINTS[name]))
        self.table.configure(state='disabled')

    def _entry(self, bar: tkinter.Frame, label: str, value: str, key: str) -> tkinter.StringVar:
        import tkinter

        tkinter.Label(bar, text=f'  {label}').pack(side='left')
        var = tkinter.StringVar(self.root, value)
        tkinter.Entry(bar, textvariable=var, width=16).pack(side='left')
        var.trace_add('write', lambda *_: self.console.set_filters(**{key: var.get()}))
        return var

    def _close(self) -> None:
        self.closed = True

    def _toggle_pause(self) -> None:
        paused = self.console.toggle_pause()
        self.pause.configure(text='Resume' if paused else 'Pause')

    def draw(self) -> None:
        """Fill the table with the rows that pass the filters, newest at the bottom."""
        rows, kept = self.console.shown(last=SHOWN_ROWS)
        sizes = widths(rows, TABLE_CHARACTERS)
        self.header.configure(text=line(COLUMNS, sizes))
        table = self.table
        table.configure(state='normal')
        table.delete('1.0', 'end')
        for row in rows:
            table.insert('end', line(cells(row), sizes) + '\n', row.severity)
        table.configure(state='disabled')
        table.see('end')
        self.status.configure(text=self.console.status(len(rows), kept))

    def run(self, ok: Callable[[], bool], period: float) -> None:
        """Redraw when the console changed, looking every `period` s, until closed or not
        `ok()`."""
        shown = None
        try:
            while not self.closed and ok():
                version = self.console.version
                if version != shown:
                    shown = version
                    self.draw()
                self.root.update()
                time.sleep(period)
        finally:
            self.root.destroy()
