"""rclpy's SIGINT and SIGTERM handlers (rclpy.signals): a signal stops the open contexts, so
spinning ends and `main()` leaves through its own clean-up; the handler that was there before
still runs. Installed by `ros2lite.init()`, removed by `ros2lite.shutdown()`.
"""

from __future__ import annotations

import enum
import os
import signal
import threading
from collections.abc import Callable
from types import FrameType

from ros2lite.context import open_contexts

__all__ = [
    'SignalHandlerOptions',
    'get_current_signal_handlers_options',
    'install_signal_handlers',
    'uninstall_signal_handlers',
]


class SignalHandlerOptions(enum.IntEnum):
    """Which of ros2lite's signal handlers are installed (rclpy's names)."""

    NO = 0
    SigInt = 1
    SigTerm = 2
    ALL = 3


# a handler signal.getsignal() may give back
_Handler = Callable[[int, FrameType | None], object] | int | signal.Handlers | None
_previous: dict[int, _Handler] = {}


def _stop_open_contexts(signum: int, frame: FrameType | None) -> None:
    """SIGINT and SIGTERM as rclpy handles them: open contexts stop being ok() and spinning
    executors end (SIGTERM: with ExternalShutdownException), so `main()` can leave through its
    normal clean-up; the handler that was there before still runs (Ctrl-C still raises
    KeyboardInterrupt). Doing the shutdown itself here could interrupt a zenoh call on this
    very thread."""
    stopped = open_contexts()
    for ctx in stopped:
        ctx.terminate()
    previous = _previous.get(signum, signal.SIG_DFL)
    if callable(previous):
        previous(signum, frame)
    elif not stopped and previous == signal.SIG_DFL:
        # nothing of ours to stop: die of the signal as if we had never been installed
        signal.signal(signum, signal.SIG_DFL)
        os.kill(os.getpid(), signum)


def _wanted(options: SignalHandlerOptions) -> list[signal.Signals]:
    return [
        sig
        for sig, flag in (
            (signal.SIGINT, SignalHandlerOptions.SigInt),
            (signal.SIGTERM, SignalHandlerOptions.SigTerm),
        )
        if options & flag
    ]


def install_signal_handlers(options: SignalHandlerOptions = SignalHandlerOptions.ALL) -> None:
    """Route the chosen signals through ros2lite's handler (main thread only; the handler
    already there is still called after ours)."""
    if threading.current_thread() is not threading.main_thread():
        return
    for sig in _wanted(SignalHandlerOptions(options)):
        current = signal.getsignal(sig)
        if current is _stop_open_contexts:
            continue
        _previous[sig] = current
        signal.signal(sig, _stop_open_contexts)


def uninstall_signal_handlers() -> None:
    """Put back the handlers that were there before :func:`install_signal_handlers`."""
    if threading.current_thread() is not threading.main_thread():
        return
    for sig, previous in list(_previous.items()):
        if signal.getsignal(sig) is _stop_open_contexts:
            signal.signal(sig, previous if previous is not None else signal.SIG_DFL)
        del _previous[sig]


def get_current_signal_handlers_options() -> SignalHandlerOptions:
    """Which of ros2lite's handlers are installed now."""
    options = 0
    if signal.getsignal(signal.SIGINT) is _stop_open_contexts:
        options |= SignalHandlerOptions.SigInt
    if signal.getsignal(signal.SIGTERM) is _stop_open_contexts:
        options |= SignalHandlerOptions.SigTerm
    return SignalHandlerOptions(options)
