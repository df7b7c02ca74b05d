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
