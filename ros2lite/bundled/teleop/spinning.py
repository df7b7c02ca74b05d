"""A node's executor on a background thread, for programs whose main thread reads keys; the
teleop programs' key loop on top of it."""

from __future__ import annotations

import contextlib
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING

from ros2lite.util.keyboard import Keyboard

if TYPE_CHECKING:
    from ros2lite.node import Node


class BackgroundSpin:
    """Spin `node` on a daemon thread until `stop()` (or shutdown); a context manager."""

    def __init__(self, node: Node) -> None:
        from ros2lite.executors import SingleThreadedExecutor

        self.node = node
        self.executor = SingleThreadedExecutor(context=node.context)
        self.executor.add_node(node)
        self._thread = threading.Thread(target=self._spin, name='teleop-executor', daemon=True)

    def _spin(self) -> None:
        from ros2lite.executors import ExternalShutdownException

        # on SIGTERM the main thread sees ok() turn False and leaves
        with contextlib.suppress(ExternalShutdownException):
            self.executor.spin()

    def __enter__(self) -> BackgroundSpin:
        self._thread.start()
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()

    def stop(self) -> None:
        """Stop spinning and wait (up to 5 s) for the thread."""
        self.executor.shutdown()
        self._thread.join(5.0)


def key_loop(node: Node, banner: str, handle: Callable[[str], bool], *, raw: bool = False) -> None:
    """Show `banner`, then pass each key to `handle` until it returns False, input ends or the
    context shuts down, with `node` spinning in the background and the terminal restored on
    every way out (what every teleop program does)."""
    context = node.context
    with BackgroundSpin(node), Keyboard(raw=raw) as keyboard:
        print(banner, flush=True)
        while context.ok():
            try:
                key = keyboard.read(0.1)
            except EOFError:
                return
            if key is not None and not handle(key):
                return
