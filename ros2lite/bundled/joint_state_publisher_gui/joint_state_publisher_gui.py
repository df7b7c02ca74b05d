"""`joint_state_publisher_gui`: the node `joint_state_publisher` (its parameters, its topics)
with a tkinter window, "Joint State Publisher", holding a slider for each free joint (its name,
its value, its range; continuous joints over [-pi, pi]) and the buttons Randomize and Center.
Moving a slider moves the joint in the next `/joint_states`; a joint set by a source topic moves
its slider. A new robot description rebuilds the sliders.

The node spins on its own thread; the window lives on the main thread (where tkinter must) and
reads and writes the model under the node's lock. Closing the window ends the node.
"""

from __future__ import annotations

import contextlib
import random
import sys
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING

from ros2lite.bundled.display import open_window
from ros2lite.bundled.joint_state_publisher.joint_state_publisher import (
    JointStatePublisher,
    urdf_argument,
)
from ros2lite.bundled.runner import run_main, spin_beside

if TYPE_CHECKING:
    import tkinter

__all__ = ['SliderWindow', 'main']

FRAME_SECONDS = 0.05
STEPS = 1000  # a slider's range in steps
MAX_ROWS = 20  # sliders per column, before a new column starts


class SliderWindow:
    """The window of sliders on a JointStatePublisher's model; `run(stop)` until closed."""

    def __init__(self, node: JointStatePublisher) -> None:
        import tkinter

        self.node = node
        self.root = open_window('joint_state_publisher_gui', 'Joint State Publisher')
        self.closed = False
        self.root.protocol('WM_DELETE_WINDOW', self._close)
        self.panel = tkinter.Frame(self.root, padx=8, pady=8)
        self.panel.pack(fill='both', expand=True)
        buttons = tkinter.Frame(self.root, padx=8, pady=4)
        buttons.pack(fill='x')
        tkinter.Button(buttons, text='Randomize', command=self.randomize).pack(side='left')
        tkinter.Button(buttons, text='Center', command=self.center).pack(side='left', padx=8)
        self.sliders: dict[str, tkinter.Scale] = {}
        self.dragging: set[str] = set()
        self._rebuild = threading.Event()
        node.on_robot.append(lambda _: self._rebuild.set())
        self._build()

    def _close(self) -> None:
        self.closed = True

    def _build(self) -> None:
        import tkinter

        for child in self.panel.winfo_children():
            child.destroy()
        self.sliders.clear()
        self.dragging.clear()
        with self.node.lock:
            free = [
                self.node.joints.free[n]
                for n in self.node.joints.names
                if n in self.node.joints.free
            ]
        if not free:
            text = (
                'Waiting for robot_description...'
                if self.node.robot is None
                else 'No movable joints'
            )
            tkinter.Label(self.panel, text=text).grid(row=0, column=0)
            return
        for i, joint in enumerate(free):
            row, column = i % MAX_ROWS, 2 * (i // MAX_ROWS)
            tkinter.Label(self.panel, text=joint.name, anchor='w').grid(
                row=row, column=column, sticky='w', padx=(0, 8)
            )
            span = joint.upper - joint.lower
            scale = tkinter.Scale(
                self.panel,
                from_=joint.lower,
                to=joint.upper,
                resolution=span / STEPS if span > 0 else 1.0,
                digits=5,
                orient='horizontal',
                length=240,
                command=self._mover(joint.name),
            )
            scale.set(joint.position)
            scale.grid(row=row, column=column + 1, sticky='we')
            scale.bind('<ButtonPress-1>', self._grab(joint.name, True))
            scale.bind('<ButtonRelease-1>', self._grab(joint.name, False))
            self.sliders[joint.name] = scale

    def _mover(self, name: str) -> Callable[[str], None]:
        """The slider's command: its value (text) becomes the joint's position."""

        def moved(value: str) -> None:
            with self.node.lock:
                joint = self.node.joints.free.get(name)
                if joint is not None:
                    joint.position = float(value)

        return moved

    def _grab(self, name: str, held: bool) -> Callable[[tkinter.Event[tkinter.Scale]], None]:
        """A press (or release) handler: a held slider is not moved by the model."""

        def grab(_: tkinter.Event[tkinter.Scale]) -> None:
            if held:
                self.dragging.add(name)
            else:
                self.dragging.discard(name)

        return grab

    def _set_all(self, choose: Callable[[float, float, float], float]) -> None:
        with self.node.lock:
            for joint in self.node.joints.free.values():
                joint.position = choose(joint.lower, joint.upper, joint.zero)

    def randomize(self) -> None:
        """Every free joint to a random place in its range."""
        self._set_all(lambda lower, upper, _zero: random.uniform(lower, upper))

    def center(self) -> None:
        """Every free joint back to its default."""
        self._set_all(lambda _lower, _upper, zero: zero)

    def _follow_model(self) -> None:
        """Sliders show where the joints are (sources and buttons move them too)."""
        with self.node.lock:
            positions = {n: j.position for n, j in self.node.joints.free.items()}
        for name, scale in self.sliders.items():
            if name in self.dragging or name not in positions:
                continue
            step = float(scale.cget('resolution'))
            if abs(float(scale.get()) - positions[name]) > step / 2:
                scale.set(positions[name])

    def run(self, stop: Callable[[], bool]) -> None:
        """Draw until the window closes or `stop()` says so."""
        import time
        import tkinter

        try:
            while not self.closed and not stop():
                if self._rebuild.is_set():
                    self._rebuild.clear()
                    self._build()
                self._follow_model()
                self.root.update()
                time.sleep(FRAME_SECONDS)
        except tkinter.TclError:
            pass  # the window went away under us: as good as closed
        finally:
            with contextlib.suppress(tkinter.TclError):
                self.root.destroy()


def _run(urdf_file: str | None) -> None:
    node = JointStatePublisher(urdf_file)
    spin_beside(node, SliderWindow(node).run, 'joint-state-publisher')


def main(args: list[str] | None = None) -> int:
    """`joint_state_publisher_gui [urdf_file]`'s entry point."""
    urdf_file = urdf_argument(args)
    return run_main(lambda: _run(urdf_file), args)


if __name__ == '__main__':
    sys.exit(main())
