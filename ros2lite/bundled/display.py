"""Where a demo shows itself: a window, the terminal, or nowhere (`--display auto`).

A window needs tkinter and a display to open on (X11's DISPLAY or Wayland's; macOS and
Windows always have one); the terminal needs stdout to be one. Otherwise nothing is drawn,
so a demo run from a script or a service writes only its log lines.
"""

from __future__ import annotations

import os
import sys
from typing import TYPE_CHECKING, TextIO

if TYPE_CHECKING:
    import argparse
    import tkinter

from ros2lite.exceptions import Ros2liteError

CHOICES = ('auto', 'window', 'terminal', 'none')


def window_possible(environ: dict[str, str] | None = None) -> bool:
    """Whether a tkinter window can be tried here (it may still fail to open)."""
    env = os.environ if environ is None else environ
    if sys.platform not in ('darwin', 'win32') and not (
        env.get('DISPLAY') or env.get('WAYLAND_DISPLAY')
    ):
        return False
    try:
        import tkinter  # noqa: F401
    except ImportError:
        return False
    return True


def terminal_possible(stream: TextIO | None = None) -> bool:
    """Whether `stream` (stdout by default) is a terminal a view can draw on."""
    stream = sys.stdout if stream is None else stream
    try:
        return stream.isatty()
    except (AttributeError, ValueError):
        return False


def choose(requested: str) -> list[str]:
    """The displays to try, best first: `auto` tries a window, then the terminal, then none;
    an explicit choice is tried alone (and is an error if it cannot open)."""
    if requested != 'auto':
        return [requested]
    order = []
    if window_possible():
        order.append('window')
    if terminal_possible():
        order.append('terminal')
    order.append('none')
    return order


class DisplayError(Ros2liteError, ValueError):
    """A display that was asked for cannot be opened (one line for the user)."""


def open_window(class_name: str, title: str) -> tkinter.Tk:
    """A new top-level tkinter window, or DisplayError saying why none can open here."""
    try:
        import tkinter
    except ImportError:
        raise DisplayError('cannot open a window: tkinter is not installed') from None
    if not window_possible():
        raise DisplayError('cannot open a window: no display (DISPLAY is not set)')
    try:
        root = tkinter.Tk(className=class_name)
    except tkinter.TclError as e:
        raise DisplayError(f'cannot open a window: {e}') from None
    root.title(title)
    return root


def add_display_argument(parser: argparse.ArgumentParser) -> None:
    """`--display auto|window|terminal|none` on a demo's argparse parser."""
    parser.add_argument(
        '--display',
        choices=CHOICES,
        default='auto',
        help='where to draw: a window, the terminal, or nowhere (default: the best available)',
    )


def own_arguments(argv: list[str] | None) -> list[str]:
    """A demo's own arguments: argv without the program name and the `--ros-args` blocks."""
    from ros2lite.runtime.arguments import split_ros_args

    user, _ = split_ros_args(list(sys.argv[1:] if argv is None else argv))
    return user
