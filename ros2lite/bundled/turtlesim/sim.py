"""The turtlesim world as a library: turtles, pens, the path canvas and one fixed update step.

No ROS, no threads, no I/O: `World.step()` advances every turtle by one 16 ms tick and returns
what happened (poses, colours under the turtles, goal feedback and outcomes, wall hits), and
the node turns that into messages and log lines. Tests and scripts can step it directly.

The numbers and the order of work inside a step are those of ROS 2 Jazzy's turtlesim node:
a 500x500 px canvas where one metre is 45 px (so the world is 499/45 = 11.088889 m square),
turtle1 at the centre facing east, commands lasting one second, turtles clamped at the walls,
rotate_absolute goals turning at 1 rad/s until within 0.02 rad, teleports drawn with the pen.
"""

from __future__ import annotations

import math
import random
import struct
from collections import deque
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Literal

# turtlesim's own (rounded) pi: angles are normalised with it, so keep it for equal results
PI = 3.14159265
TWO_PI = 2.0 * PI

CANVAS_PX = 500
METER_PX = 45  # the height of a turtle image is one metre
WIDTH = (CANVAS_PX - 1) / METER_PX
HEIGHT = (CANVAS_PX - 1) / METER_PX
DT = 0.016  # one update of the 16 ms timer
RATE_HZ = 1.0 / DT
COMMAND_TIMEOUT = 1.0  # a Twist moves the turtle for this long
GOAL_TOLERANCE = 0.02  # rad: a rotate_absolute goal is reached within this
GOAL_SPEED = 1.0  # rad/s while turning towards a goal

DEFAULT_BACKGROUND = (69, 86, 255)
DEFAULT_PEN = (0xB3, 0xB8, 0xFF)
DEFAULT_PEN_WIDTH = 3
# an untouched canvas pixel: turtlesim's path image is cleared to transparent white, and its
# colour sensor reads that image, so off the trails it reports white
EMPTY_PIXEL = (255, 255, 255)

SPRITE_COUNT = 12  # looks to pick from (the views colour them); one chosen at random per turtle

_F32 = struct.Struct('<f')


def f32(value: float) -> float:
    """`value` rounded to float32, as it is in the messages (and in turtlesim's casts)."""
    return float(_F32.unpack(_F32.pack(value))[0])


def normalize_angle(angle: float) -> float:
    """Into [-pi, pi), with turtlesim's formula and constants."""
    return angle - TWO_PI * math.floor((angle + PI) / TWO_PI)


@dataclass
class Pen:
    """What a turtle draws with; `off` draws nothing."""

    r: int = DEFAULT_PEN[0]
    g: int = DEFAULT_PEN[1]
    b: int = DEFAULT_PEN[2]
    width: int = DEFAULT_PEN_WIDTH
    off: bool = False

    @property
    def rgb(self) -> tuple[int, int, int]:
        """The pen's colour."""
        return (self.r, self.g, self.b)


@dataclass(frozen=True)
class Pose:
    """A turtle's pose as /pose carries it (world metres, y up, theta in [-pi, pi))."""

    x: float
    y: float
    theta: float
    linear_velocity: float
    angular_velocity: float


@dataclass
class RotateGoal:
    """A rotate_absolute goal a turtle is working on. `token` is the caller's (the node keeps
    its goal handle there); `cancel_requested` is set from outside and honoured at the next step.
    """

    theta: float
    start_theta: float = 0.0
    token: object = None
    cancel_requested: bool = False
    delta: float = 0.0  # turned so far (start - now), the action's result


@dataclass(frozen=True)
class GoalFeedback:
    """A rotate goal's progress after a step (what the action publishes)."""

    turtle: str
    goal: RotateGoal
    remaining: float


@dataclass(frozen=True)
class GoalDone:
    """A goal ended: 'succeeded', 'canceled' or 'aborted' (aborted ones come from `command`
    and `start_goal`, the other two from `step`)."""

    turtle: str
    goal: RotateGoal
    outcome: str


@dataclass(frozen=True)
class WallHit:
    """The turtle left the canvas and was clamped; x, y in turtlesim's screen frame (y down),
    which is what its warning prints."""

    turtle: str
    x: float
    y: float


Event = GoalFeedback | GoalDone | WallHit
"""Something a step did that the node reports (feedback, a goal's end, a wall)."""


@dataclass
class TurtleUpdate:
    """What one step did to one turtle: everything the node publishes or logs for it."""

    name: str
    pose: Pose
    color: tuple[int, int, int]
    events: list[Event] = field(default_factory=list)


@dataclass(frozen=True)
class _Teleport:
    x: float
    y: float
    theta: float
    linear: float
    relative: bool


class Turtle:
    """One turtle: pose, velocities, pen, queued teleports and the goal it works on."""

    def __init__(self, name: str, x: float, y: float, theta: float, sprite: int = 0) -> None:
        self.name = name
        self.x = x
        self.y = y
        self.theta = theta
        self.lin_x = 0.0
        self.lin_y = 0.0
        self.ang = 0.0
        self.pen = Pen()
        self.sprite = sprite
        self.last_command = 0.0  # world time of the last Twist (or goal turn)
        self.goal: RotateGoal | None = None
        self._teleports: list[_Teleport] = []

    def pose(self) -> Pose:
        """The pose /pose publishes (float32 values, as turtlesim's message)."""
        return Pose(
            f32(self.x),
            f32(self.y),
            f32(self.theta),
            f32(math.hypot(self.lin_x, self.lin_y)),
            f32(self.ang),
        )

    # -- inputs (applied as turtlesim applies them: velocities now, teleports at the next step)
    def command(
        self, linear_x: float, linear_y: float, angular_z: float, now: float, holonomic: bool
    ) -> GoalDone | None:
        """A Twist: sets the velocities for the next second; aborts a running goal (returned).
        Without `holonomic` the sideways velocity is left as it was, as turtlesim does."""
        self.last_command = now
        self.lin_x = linear_x
        if holonomic:
            self.lin_y = linear_y
        self.ang = angular_z
        goal, self.goal = self.goal, None
        return GoalDone(self.name, goal, 'aborted') if goal is not None else None

    def set_pen(self, r: int, g: int, b: int, width: int, off: bool) -> None:
        """SetPen: `off` lifts the pen and keeps its colour; width 0 means a 1 px pen."""
        self.pen.off = bool(off)
        if off:
            return
        self.pen = Pen(r, g, b, width if width != 0 else 1, False)

    def teleport_absolute(self, x: float, y: float, theta: float) -> None:
        """Move to (x, y, theta) at the next step, drawing if the pen is down."""
        self._teleports.append(_Teleport(x, y, theta, 0.0, False))

    def teleport_relative(self, linear: float, angular: float) -> None:
        """Turn, then move `linear` ahead, at the next step."""
        self._teleports.append(_Teleport(0.0, 0.0, angular, linear, True))

    def take_teleports(self) -> list[_Teleport]:
        """The teleports asked for since the last step, in order (handed out once)."""
        teleports, self._teleports = self._teleports, []
        return teleports

    def start_goal(self, goal: RotateGoal) -> GoalDone | None:
        """Work on `goal` from the next step; a goal still running is aborted (returned)."""
        previous = self.goal
        goal.start_theta = self.theta
        self.goal = goal
        return GoalDone(self.name, previous, 'aborted') if previous is not None else None


Stroke = (
    tuple[Literal['clear']]
    | tuple[Literal['line'], float, float, float, float, tuple[int, int, int], int]
)
"""What a view replays: ('line', x0, y0, x1, y1, rgb, width) or ('clear',)."""


class Canvas:
    """The path image (500x500 RGBA, transparent where nothing was drawn) and, for a view, the
    log of what was drawn since it last looked (`drain()`)."""

    def __init__(self, size: int = CANVAS_PX) -> None:
        self.size = size
        self.pixels = bytearray(size * size * 4)
        self.keep_strokes = False  # a view sets it, then must drain()
        self._strokes: deque[Stroke] = deque()
        self.clear()

    def clear(self) -> None:
        """Wipe every path (a view replays it as 'clear')."""
        self.pixels[:] = bytes((*EMPTY_PIXEL, 0)) * (self.size * self.size)
        if self.keep_strokes:
            self._strokes.append(('clear',))

    def pixel(self, px: int, py: int) -> tuple[int, int, int]:
        """The colour at a pixel (an untouched one reads as white, as in turtlesim); outside
        the image: black, as QImage::pixel answers."""
        if not (0 <= px < self.size and 0 <= py < self.size):
            return (0, 0, 0)
        i = (py * self.size + px) * 4
        return (self.pixels[i], self.pixels[i + 1], self.pixels[i + 2])

    def is_drawn(self, px: int, py: int) -> bool:
        """Whether a path crossed this pixel."""
        return (
            0 <= px < self.size
            and 0 <= py < self.size
            and bool(self.pixels[(py * self.size + px) * 4 + 3])
        )

    def draw_line(
        self, x0: float, y0: float, x1: float, y1: float, rgb: tuple[int, int, int], width: int
    ) -> None:
        """A line in pixel coordinates with square ends, `width` px thick."""
        opaque = bytes((*rgb, 255))
        for left, top, right, bottom in line_squares(x0, y0, x1, y1, width):
            left, top = max(left, 0), max(top, 0)
            right, bottom = min(right, self.size), min(bottom, self.size)
            if left >= right:
                continue
            run = opaque * (right - left)
            for row in range(top, bottom):
                start = (row * self.size + left) * 4
                self.pixels[start : start + len(run)] = run
        if self.keep_strokes:
            self._strokes.append(('line', x0, y0, x1, y1, rgb, width))

    def has_strokes(self) -> bool:
        """Whether strokes wait for a view to drain them."""
        return bool(self._strokes)

    def drain(self) -> list[Stroke]:
        """Strokes drawn since the last call: ('line', x0, y0, x1, y1, rgb, width) or ('clear',)."""
        out = []
        while True:
            try:
                out.append(self._strokes.popleft())
            except IndexError:
                return out


def line_squares(
    x0: float, y0: float, x1: float, y1: float, width: int
) -> Iterator[tuple[int, int, int, int]]:
    """Pixel squares (left, top, right, bottom; right/bottom exclusive) covering a thick line:
    one square of side `width` every half pixel along it. Views use it to draw the same trail."""
    width = max(int(width), 1)
    half = width / 2.0
    steps = max(1, math.ceil(2 * max(abs(x1 - x0), abs(y1 - y0))))
    last = None
    for i in range(steps + 1):
        t = i / steps
        cx = x0 + (x1 - x0) * t
        cy = y0 + (y1 - y0) * t
        left = math.floor(cx - half + 0.5)
        top = math.floor(cy - half + 0.5)
        square = (left, top, left + width, top + width)
        if square != last:
            last = square
            yield square


class World:
    """All turtles on one canvas, stepped at a fixed 16 ms; time is the world's own (steps
    times 16 ms), which is what a command's one second is measured in."""

    def __init__(self, rng: random.Random | None = None) -> None:
        self.turtles: dict[str, Turtle] = {}
        self.canvas = Canvas()
        self.time = 0.0
        self.steps = 0
        self.holonomic = False
        self.background = DEFAULT_BACKGROUND
        self._id_counter = 0
        self._rng = rng or random.Random()

    # -- world-level requests ----------------------------------------------------------------
    def spawn(self, name: str, x: float, y: float, theta: float) -> str:
        """A new turtle; an empty name picks the next free `turtleN`. Returns its name, or ''
        when the name is taken (turtlesim's answer)."""
        if not name:
            while True:
                self._id_counter += 1
                name = f'turtle{self._id_counter}'
                if name not in self.turtles:
                    break
        elif name in self.turtles:
            return ''
        self.turtles[name] = Turtle(
            name, f32(x), f32(y), f32(theta), self._rng.randrange(SPRITE_COUNT)
        )
        return name

    def kill(self, name: str) -> bool:
        """Remove a turtle; False if there is none of that name."""
        return self.turtles.pop(name, None) is not None

    def clear(self) -> None:
        """Wipe the paths (the turtles stay)."""
        self.canvas.clear()

    def remove_all(self) -> list[Turtle]:
        """Every turtle goes and names count from turtle1 again; returns the turtles removed."""
        gone = list(self.turtles.values())
        self.turtles.clear()
        self._id_counter = 0
        return gone

    def reset(self) -> list[Turtle]:
        """/reset: every turtle goes, turtle1 comes back at the centre, the canvas is cleared;
        returns the turtles removed."""
        gone = self.remove_all()
        self.spawn('', WIDTH / 2.0, HEIGHT / 2.0, 0.0)
        self.clear()
        return gone

    # -- the update ---------------------------------------------------------------------------
    def step(self) -> list[TurtleUpdate]:
        """One 16 ms tick for every turtle (in name order, as turtlesim's map iterates)."""
        self.steps += 1
        self.time = self.steps * DT
        return [self._update(self.turtles[name]) for name in sorted(self.turtles)]

    def _update(self, t: Turtle) -> TurtleUpdate:
        events: list[Event] = []
        canvas = self.canvas
        # teleports first, in order, each drawn with the pen
        for req in t.take_teleports():
            old = (t.x, t.y)
            if req.relative:
                t.theta += req.theta
                t.x += math.cos(t.theta) * req.linear
                t.y += math.sin(t.theta) * req.linear
            else:
                t.x = req.x
                t.y = min(req.y, HEIGHT)  # turtlesim clamps only this one at once
                t.theta = req.theta
            if not t.pen.off:
                canvas.draw_line(*_px(*old), *_px(t.x, t.y), t.pen.rgb, t.pen.width)

        goal = t.goal
        if goal is not None:
            if goal.cancel_requested:
                t.goal = None
                t.lin_x = t.lin_y = t.ang = 0.0
                events.append(GoalDone(t.name, goal, 'canceled'))
            else:
                target = normalize_angle(goal.theta)
                remaining = normalize_angle(target - f32(t.theta))
                goal.delta = normalize_angle(f32(goal.start_theta - t.theta))
                events.append(GoalFeedback(t.name, goal, remaining))
                if abs(normalize_angle(f32(t.theta) - target)) < GOAL_TOLERANCE:
                    t.goal = None
                    t.lin_x = t.lin_y = t.ang = 0.0
                    events.append(GoalDone(t.name, goal, 'succeeded'))
                else:
                    t.lin_x = t.lin_y = 0.0
                    t.ang = -GOAL_SPEED if remaining < 0.0 else GOAL_SPEED
                    t.last_command = self.time

        if self.time - t.last_command > COMMAND_TIMEOUT + 1e-9:
            t.lin_x = t.lin_y = t.ang = 0.0

        old = (t.x, t.y)
        t.theta = normalize_angle(t.theta + t.ang * DT)
        cos, sin = math.cos(t.theta), math.sin(t.theta)
        t.x += (cos * t.lin_x - sin * t.lin_y) * DT
        t.y += (sin * t.lin_x + cos * t.lin_y) * DT
        if not (0.0 <= t.x <= WIDTH and 0.0 <= t.y <= HEIGHT):
            events.append(WallHit(t.name, t.x, HEIGHT - t.y))
        t.x = min(max(t.x, 0.0), WIDTH)
        t.y = min(max(t.y, 0.0), HEIGHT)

        px, py = _px(t.x, t.y)
        color = canvas.pixel(math.floor(px + 0.5), math.floor(py + 0.5))
        update = TurtleUpdate(t.name, t.pose(), color, events)
        if (t.x, t.y) != old and not t.pen.off:
            canvas.draw_line(*_px(*old), px, py, t.pen.rgb, t.pen.width)
        return update


def _px(x: float, y: float) -> tuple[float, float]:
    """World metres (y up) to canvas pixels (y down)."""
    return x * METER_PX, (HEIGHT - y) * METER_PX
