"""`turtlesim_node`: the `/turtlesim` node, drawn in a window, on the terminal, or not at all.

The node spins on its own thread (its 16 ms step never waits for a drawing); the view runs on
the main thread, where tkinter must live and where Ctrl-C arrives. Closing the window ends
the node, as closing turtlesim's window does.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable
from typing import TYPE_CHECKING

from ros2lite.bundled.display import DisplayError, add_display_argument, choose, own_arguments
from ros2lite.bundled.runner import run_main, spin_beside

if TYPE_CHECKING:
    from ros2lite.bundled.turtlesim.node import TurtlesimNode


def open_view(kind: str, node: TurtlesimNode) -> Callable[[Callable[[], bool]], None] | None:
    """A started view of `kind` ('window', 'terminal'), as a blocking `run(stop)`; None for
    'none'. Raises DisplayError when it cannot open."""
    if kind == 'window':
        from ros2lite.bundled.turtlesim.window_view import WindowView

        return WindowView(node).run
    if kind == 'terminal':
        from ros2lite.bundled.turtlesim.terminal_view import TerminalView

        return TerminalView(node).run
    return None


def run_with_display(node: TurtlesimNode, requested: str) -> None:
    """Spin `node` and show it on the first display of `requested` that opens."""
    from ros2lite.executors import SingleThreadedExecutor

    run = None
    errors = []
    for kind in choose(requested):
        try:
            run = open_view(kind, node)
            break
        except DisplayError as e:
            errors.append(str(e))
    else:
        raise DisplayError(errors[-1] if errors else 'no display')

    if run is None:
        executor = SingleThreadedExecutor(context=node.context)
        executor.add_node(node)
        executor.spin()
        return
    spin_beside(node, run, 'turtlesim-executor')


def main(args: list[str] | None = None) -> int:
    """`turtlesim_node`'s entry point (`--display auto|window|terminal|none`)."""
    parser = argparse.ArgumentParser(
        prog='turtlesim_node', description='The turtlesim node (Jazzy\'s interface).'
    )
    add_display_argument(parser)
    options = parser.parse_args(own_arguments(args))

    def body() -> None:
        from ros2lite.bundled.turtlesim.node import TurtlesimNode

        run_with_display(TurtlesimNode(), options.display)

    return run_main(body, args)


if __name__ == '__main__':
    raise SystemExit(main())
