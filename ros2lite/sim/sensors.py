"""The robot's sensors as the world answers them: a planar laser, an IMU and an RGB camera.

Each is a frozen spec (what the robot's description says: beams, range, rate, noise, mount)
and a pure function from the world and the sensor's pose to readings, so the node only
stamps and publishes them. The camera is a first-person view drawn one column per ray
(walls at the world's wall height in their colours, shaded with distance, over a floor and a
sky): enough to see what is in front of the robot.
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass

from PIL import Image, ImageDraw

from ros2lite.sim.rays import fan
from ros2lite.sim.world import Grid

__all__ = [
    'CameraSpec',
    'ImuSpec',
    'LaserSpec',
    'LaserTables',
    'camera_angles',
    'render_camera',
    'scan',
]


@dataclass(frozen=True)
class LaserSpec:
    """A planar laser: its topic, frame, beams, range, rate, noise and mount on the base."""

    topic: str
    frame_id: str
    samples: int
    angle_min: float
    angle_max: float
    range_min: float
    range_max: float
    rate: float
    noise: float = 0.0
    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0

    @property
    def increment(self) -> float:
        return (self.angle_max - self.angle_min) / max(1, self.samples - 1)


@dataclass(frozen=True)
class ImuSpec:
    """An IMU: topic, frame, rate, and gyro/accelerometer noise (stddev)."""

    topic: str
    frame_id: str
    rate: float
    gyro_noise: float = 0.0
    accel_noise: float = 0.0


@dataclass(frozen=True)
class CameraSpec:
    """A pinhole RGB camera looking along the base's x axis from its mount."""

    image_topic: str
    info_topic: str
    frame_id: str
    width: int
    height: int
    hfov: float
    rate: float
    x: float = 0.0
    y: float = 0.0
    z: float = 0.3
    far: float = 30.0

    @property
    def focal(self) -> float:
        return (self.width / 2) / math.tan(self.hfov / 2)


class LaserTables:
    """A laser's beam directions relative to its mount, computed once."""

    def __init__(self, spec: LaserSpec) -> None:
        self.spec = spec
        self.angles = [spec.angle_min + n * spec.increment for n in range(spec.samples)]


def scan(
    world: Grid,
    tables: LaserTables,
    x: float,
    y: float,
    yaw: float,
    rng: random.Random,
) -> list[float]:
    """One sweep from the base at (x, y, yaw): a range per beam, inf where nothing is seen
    within range, Gaussian noise on every hit."""
    spec = tables.spec
    cy, sy = math.cos(yaw), math.sin(yaw)
    ox = x + spec.x * cy - spec.y * sy
    oy = y + spec.x * sy + spec.y * cy
    limit = spec.range_max + 3 * spec.noise
    hits, _ = fan(world.outlines, ox, oy, yaw + spec.yaw, tables.angles, limit)
    gauss, noise = rng.gauss, spec.noise
    lo, hi, inf = spec.range_min, spec.range_max, math.inf
    ranges = []
    for r in hits:
        if r != inf and noise > 0:
            r += gauss(0.0, noise)
        ranges.append(r if lo <= r <= hi else inf)
    return ranges


def camera_angles(spec: CameraSpec) -> list[float]:
    """Each image column's ray angle from the optical axis (left of centre positive),
    ascending: the last column first."""
    f = spec.focal
    return [math.atan2(spec.width / 2 - (u + 0.5), f) for u in reversed(range(spec.width))]


def render_camera(world: Grid, spec: CameraSpec, x: float, y: float, yaw: float) -> bytes:
    """An rgb8 picture (row-major, top row first) of the world from the camera's pose."""
    w, h = spec.width, spec.height
    picture = Image.new('RGB', (w, h), (178, 204, 230))
    draw = ImageDraw.Draw(picture)
    horizon = h / 2
    draw.rectangle((0, int(horizon), w, h), fill=(96, 96, 90))
    cy, sy = math.cos(yaw), math.sin(yaw)
    ox = x + spec.x * cy - spec.y * sy
    oy = y + spec.x * sy + spec.y * cy
    f = spec.focal
    top_above = world.wall_height - spec.z
    palette = world.palette or [(170, 170, 170)]
    angles = camera_angles(spec)
    distances, colours = fan(world.outlines, ox, oy, yaw, angles, spec.far)
    for k, distance in enumerate(distances):
        if distance == math.inf:
            continue
        u = w - 1 - k
        depth = max(1e-3, distance * math.cos(angles[k]))
        top = horizon - f * top_above / depth
        bottom = horizon + f * spec.z / depth
        shade = 1.0 / (1.0 + 0.12 * depth)
        colour = colours[k]
        r, g, b = palette[colour] if 0 <= colour < len(palette) else palette[0]
        draw.line(
            (u, max(0, int(top)), u, min(h - 1, int(bottom))),
            fill=(int(r * shade), int(g * shade), int(b * shade)),
        )
    return picture.tobytes()
