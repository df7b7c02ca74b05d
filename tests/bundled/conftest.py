"""Fixtures of the demo tests: a virtual X display for window tests (Xvfb on a display number
it picks itself), or a skip that says why when Xvfb (or xwd, for screenshots) is missing."""

from __future__ import annotations

import os
import shutil
import subprocess
from collections.abc import Iterator
from contextlib import contextmanager

import pytest


def xvfb_missing() -> str:
    """Why no window can be tested here ('' when it can)."""
    try:
        import tkinter  # noqa: F401
    except ImportError:
        return 'tkinter is not installed: no window to test (apt-get install python3-tk)'
    missing = [tool for tool in ('Xvfb', 'xwd') if shutil.which(tool) is None]
    if missing:
        return (
            f'{" and ".join(missing)} not installed: window tests need a virtual X display '
            '(apt-get install xvfb x11-apps)'
        )
    return ''


@contextmanager
def xvfb() -> Iterator[str]:
    """`:N` of a fresh 24-bit Xvfb screen, gone after the block."""
    read_end, write_end = os.pipe()
    proc = subprocess.Popen(
        ['Xvfb', '-displayfd', str(write_end), '-screen', '0', '640x520x24', '-nolisten', 'tcp'],
        pass_fds=(write_end,),
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    os.close(write_end)
    try:
        with os.fdopen(read_end) as f:
            number = f.readline().strip()
        assert number, 'Xvfb did not start'
        yield f':{number}'
    finally:
        proc.terminate()
        proc.wait(10)


@pytest.fixture
def xdisplay() -> Iterator[str]:
    """`:N` of a fresh 24-bit Xvfb screen, gone after the test."""
    why = xvfb_missing()
    if why:
        pytest.skip(why)
    with xvfb() as display:
        yield display
