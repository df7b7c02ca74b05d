"""The `main()` body every demo shares: init, build the node, spin, leave quietly.

Demos are run by `ros2lite run` and by hand, where Ctrl-C (or SIGTERM from a supervisor) is
the normal way out, so either ends with status 0 and no traceback (as the rclpy demos do).
Start-up errors a user can fix — no router, missing security material, bad `--ros-args`, an
invalid remapped name — become one line on stderr and status 1.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ros2lite.node import Node


def run_node(make_node: Callable[[], Node], args: list[str] | None = None) -> int:
    """Spin the node `make_node()` builds until Ctrl-C or shutdown; returns the exit status."""
    import ros2lite

    return run_main(lambda: ros2lite.spin(make_node()), args)


def run_main(body: Callable[[], object], args: list[str] | None = None) -> int:
    """Run `body()` in an initialised context (demos that do something and end)."""
    import ros2lite
    from ros2lite.exceptions import Ros2liteError
    from ros2lite.executors import ExternalShutdownException

    try:
        with ros2lite.init(args=args):
            body()
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    except (Ros2liteError, ValueError) as e:  # something the user can fix: one line
        print(str(e), file=sys.stderr, flush=True)
        return 1
    return 0


def rqt_node_name() -> str:
    """The name of the node an rqt tool runs (rqt's own: one per process)."""
    return f'rqt_gui_py_node_{os.getpid()}'


def spin_beside(node: Node, run: Callable[[Callable[[], bool]], object], name: str) -> None:
    """Spin `node` in a thread while `run(done)` holds the calling thread (a window's or a
    terminal's loop, which must own the main thread); `done()` turns True once spinning ends
    or the context shuts down. What ended the spin (SIGTERM's ExternalShutdownException) is
    raised here after the loop, so the caller leaves as a plain spin would."""
    import threading

    from ros2lite.executors import SingleThreadedExecutor

    executor = SingleThreadedExecutor(context=node.context)
    executor.add_node(node)
    failure: list[BaseException] = []

    def spin() -> None:
        try:
            executor.spin()
        except BaseException as e:  # carried to the calling thread (SIGTERM: ExternalShutdown)
            failure.append(e)

    thread = threading.Thread(target=spin, name=name, daemon=True)
    thread.start()
    try:
        run(lambda: not thread.is_alive() or not node.context.ok())
    finally:
        executor.shutdown()
        thread.join(5.0)
    if failure:
        raise failure[0]
