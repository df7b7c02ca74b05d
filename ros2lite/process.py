"""Child processes and stop signals, as `run` needs them now and `launch` next.

Signals are a process-wide resource, so everything that installs a handler does it here,
for a bounded stretch of code (a ``with`` block or one call), and puts back what was there.
Ctrl-C typed in a terminal reaches a child by itself (same foreground process group), so it
is forwarded only when it did not come from the terminal (``kill -INT``, a test, a
supervisor) or when it is the second one; SIGTERM is always forwarded.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import threading
from collections.abc import Callable, Iterator, Mapping, Sequence
from types import FrameType

from ros2lite.exceptions import Ros2liteError

__all__ = [
    'ChildError',
    'StopSignals',
    'Terminated',
    'exit_code',
    'run_child',
    'sigterm_raises',
    'switch_interval',
    'terminal_signals_child',
]

_Handler = Callable[[int, FrameType | None], object] | int | signal.Handlers | None


class ChildError(Ros2liteError, OSError):
    """A child process could not be started; the message names the command and why."""


class Terminated(BaseException):
    """SIGTERM, raised where the main thread is, so ``with`` blocks close sessions on the
    way out (a BaseException: nothing that catches ``Exception`` swallows it)."""


def _in_main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


@contextlib.contextmanager
def _handlers(handlers: dict[int, _Handler]) -> Iterator[None]:
    """Install `handlers` for the block (main thread only; elsewhere a no-op)."""
    if not _in_main_thread():
        yield
        return
    previous = {sig: signal.signal(sig, handler) for sig, handler in handlers.items()}
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler if handler is not None else signal.SIG_DFL)


@contextlib.contextmanager
def sigterm_raises() -> Iterator[None]:
    """Within the block, SIGTERM raises :class:`Terminated` in the main thread."""

    def raise_terminated(_signum: int, _frame: FrameType | None) -> None:
        raise Terminated()

    with _handlers({signal.SIGTERM: raise_terminated}):
        yield


class StopSignals:
    """SIGINT and SIGTERM only set :attr:`event` inside the block: a long job (recording a
    bag) finishes cleanly instead of being cut short by a second Ctrl-C."""

    def __init__(self) -> None:
        self.event = threading.Event()
        self._block: contextlib.ExitStack | None = None

    def _handle(self, _signum: int, _frame: FrameType | None) -> None:
        self.event.set()

    def __enter__(self) -> StopSignals:
        self._block = contextlib.ExitStack()
        self._block.enter_context(
            _handlers({signal.SIGINT: self._handle, signal.SIGTERM: self._handle})
        )
        return self

    def __exit__(self, *exc: object) -> None:
        if self._block is not None:
            self._block.close()
            self._block = None


def terminal_signals_child() -> bool:
    """True when we run in the foreground of a terminal, where Ctrl-C hits the whole process
    group — the child included — so forwarding it would deliver it twice."""
    try:
        fd = os.open('/dev/tty', os.O_RDONLY | os.O_NOCTTY)
    except OSError:
        return False
    try:
        return os.tcgetpgrp(fd) == os.getpgrp()
    except OSError:
        return False
    finally:
        os.close(fd)


def run_child(cmd: Sequence[str], env: Mapping[str, str] | None = None) -> int:
    """Start `cmd` (in `env`, default ours), forward SIGINT/SIGTERM to it (see the module
    doc), return its returncode (negative: killed by that signal).

    Signals are taken by handlers installed before the child starts, not as
    KeyboardInterrupt: a Ctrl-C landing between the child's start and our wait would
    otherwise end this process early, and the terminal would hang up on the child.
    """
    proc: subprocess.Popen[bytes] | None = None
    interrupts = 0
    terminated = False

    def forward_int(_signum: int, _frame: FrameType | None) -> None:
        nonlocal interrupts
        interrupts += 1
        if (
            proc is not None
            and proc.poll() is None
            and (interrupts > 1 or not terminal_signals_child())
        ):
            proc.send_signal(signal.SIGINT)

    def forward_term(signum: int, _frame: FrameType | None) -> None:
        nonlocal terminated
        terminated = True
        if proc is not None and proc.poll() is None:
            proc.send_signal(signum)

    with _handlers({signal.SIGINT: forward_int, signal.SIGTERM: forward_term}):
        try:
            try:
                proc = subprocess.Popen(list(cmd), env=None if env is None else dict(env))
            except OSError as e:
                raise ChildError(f'{cmd[0]}: {e.strerror or e}') from None
            # signals that came while the child was starting (it may already run and be
            # seen running, so a SIGTERM then is no rarer than one later)
            if terminated:
                proc.send_signal(signal.SIGTERM)
            elif interrupts and not terminal_signals_child():
                proc.send_signal(signal.SIGINT)
            return proc.wait()
        finally:
            sys.stdout.flush()


def exit_code(returncode: int) -> int:
    """A shell's exit status for a child's returncode (killed by signal N → 128 + N)."""
    return 128 - returncode if returncode < 0 else returncode


@contextlib.contextmanager
def switch_interval(seconds: float) -> Iterator[None]:
    """This process' thread switch interval at most `seconds` within the block: for the
    process' owner (e.g. `bag play`) when one thread must run on time while others work,
    never for a library object on its own."""
    previous = sys.getswitchinterval()
    sys.setswitchinterval(min(previous, seconds))
    try:
        yield
    finally:
        sys.setswitchinterval(previous)
