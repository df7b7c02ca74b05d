"""A node's executor on a background thread, for programs whose main thread reads keys."""

from __future__ import annotations

import contextlib
import threading
from typing import TYPE_CHECKING

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
