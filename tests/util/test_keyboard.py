"""`Keyboard` on a real pseudo-terminal and on a pipe: keys one by one, arrows decoded, the
terminal's settings put back."""

from __future__ import annotations

import os
import pty
import termios

import pytest

from ros2lite.util.keyboard import Keyboard


def test_keys_and_arrows_on_a_terminal() -> None:
    master, slave = pty.openpty()
    try:
        before = termios.tcgetattr(slave)
        with Keyboard(slave) as keyboard:
            mode = termios.tcgetattr(slave)
            assert not mode[3] & (termios.ICANON | termios.ECHO)
            assert mode[3] & termios.ISIG  # Ctrl-C still interrupts
            assert keyboard.read(0.05) is None
            os.write(master, b'x\x1b[A\x1b[D\x1bOB')
            assert [keyboard.read(1.0) for _ in range(4)] == ['x', 'up', 'left', 'down']
            os.write(master, b'\x1b')
            assert keyboard.read(1.0) == '\x1b'  # a lone Escape stays itself
        assert termios.tcgetattr(slave) == before
        with Keyboard(slave, raw=True):
            assert not termios.tcgetattr(slave)[3] & termios.ISIG  # Ctrl-C is a key
        assert termios.tcgetattr(slave) == before
        # restored on an exception too
        with pytest.raises(RuntimeError), Keyboard(slave):
            raise RuntimeError('boom')
        assert termios.tcgetattr(slave) == before
    finally:
        os.close(master)
        os.close(slave)


def test_keys_from_a_pipe_end_with_eof() -> None:
    read_end, write_end = os.pipe()
    try:
        os.write(write_end, b'ab')
        os.close(write_end)
        with Keyboard(read_end) as keyboard:
            assert keyboard.read(1.0) == 'a' and keyboard.read(1.0) == 'b'
            with pytest.raises(EOFError):
                keyboard.read(1.0)
    finally:
        os.close(read_end)
