"""Messages as the arrays a browser scene draws: scan and cloud points with their colours, a
map as an image, poses as viser's (w, x, y, z) quaternions. Pure functions of the message, so
the render loop (not the subscription callback) pays for them, and tests call them directly."""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from ros2lite.exceptions import Ros2liteError
from ros2lite.msgs.geometry_msgs.msg import Pose as PoseMsg
from ros2lite.msgs.nav_msgs.msg import OccupancyGrid
from ros2lite.msgs.sensor_msgs.msg import Image, LaserScan, PointCloud2
from ros2lite.msgs.std_msgs.msg import Header
from ros2lite.tf2.math import compose

Floats = npt.NDArray[np.float32]
Bytes = npt.NDArray[np.uint8]
Vec = tuple[float, float, float]
Quat = tuple[float, float, float, float]  # x, y, z, w as ROS writes it
Pose = tuple[Vec, Quat]

IDENTITY: Pose = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))

# PointField datatypes -> numpy scalar types (sensor_msgs/PointField's constants)
_FIELD_TYPES: dict[int, str] = {
    1: 'i1',
    2: 'u1',
    3: 'i2',
    4: 'u2',
    5: 'i4',
    6: 'u4',
    7: 'f4',
    8: 'f8',
}


class ConvertError(Ros2liteError, ValueError):
    """A message whose layout cannot be drawn (says which part, in one line)."""


def wxyz(q: Quat) -> tuple[float, float, float, float]:
    """ROS's (x, y, z, w) as viser's (w, x, y, z), normalised (a zero quaternion: identity)."""
    x, y, z, w = q
    n = math.sqrt(x * x + y * y + z * z + w * w)
    if n < 1e-12 or not math.isfinite(n):
        return (1.0, 0.0, 0.0, 0.0)
    return (w / n, x / n, y / n, z / n)


def pose_of(msg_pose: PoseMsg) -> Pose:
    """A geometry_msgs/Pose as (position, orientation) tuples."""
    p = msg_pose.position
    o = msg_pose.orientation
    return (float(p.x), float(p.y), float(p.z)), (float(o.x), float(o.y), float(o.z), float(o.w))


def then(outer: Pose, inner: Pose) -> Pose:
    """`inner` expressed in the frame `outer` places (outer ∘ inner)."""
    return compose(outer, inner)


def stamp_ns(header: Header) -> int:
    """A header's stamp in nanoseconds (0: 'the latest', as tf2 reads it)."""
    stamp = header.stamp
    return int(stamp.sec) * 1_000_000_000 + int(stamp.nanosec)


def decimate(points: Floats, colours: Bytes, budget: int) -> tuple[Floats, Bytes]:
    """At most `budget` points, taken evenly (a stride) so the shape stays whole."""
    n = len(points)
    if budget <= 0 or n <= budget:
        return points, colours
    step = math.ceil(n / budget)
    return points[::step], colours[::step]


def scan_points(scan: LaserScan) -> Floats:
    """A LaserScan's valid returns (range_min <= r <= range_max, finite) as x, y, z rows."""
    ranges = np.asarray(scan.ranges, dtype=np.float32)
    if ranges.size == 0:
        return np.zeros((0, 3), np.float32)
    angles = scan.angle_min + scan.angle_increment * np.arange(ranges.size)
    ok = np.isfinite(ranges) & (ranges >= scan.range_min) & (ranges <= scan.range_max)
    r, a = ranges[ok], angles[ok]
    out = np.zeros((r.size, 3), np.float32)
    out[:, 0] = r * np.cos(a)
    out[:, 1] = r * np.sin(a)
    return out


def intensity_colours(values: npt.NDArray[np.floating]) -> Bytes:
    """RViz's default 'Intensity' colouring: a rainbow from the lowest value to the highest."""
    if values.size == 0:
        return np.zeros((0, 3), np.uint8)
    finite = values[np.isfinite(values)]
    low, high = (float(finite.min()), float(finite.max())) if finite.size else (0.0, 1.0)
    t = np.clip((values - low) / (high - low if high > low else 1.0), 0.0, 1.0)
    t = np.nan_to_num(t)
    # red (high) through yellow, green, cyan to blue (low): hue from 0 to 240 degrees
    h = (1.0 - t) * 4.0
    c = np.zeros((values.size, 3), np.float32)
    x = 1.0 - np.abs(np.mod(h, 2.0) - 1.0)
    for lo, rgb in ((0, (1, x, 0)), (1, (x, 1, 0)), (2, (0, 1, x)), (3, (0, x, 1))):
        sel = (h >= lo) & (h < lo + 1) if lo < 3 else h >= lo
        for channel, v in enumerate(rgb):
            c[sel, channel] = v[sel] if isinstance(v, np.ndarray) else v
    return (c * 255).astype(np.uint8)


def cloud_points(cloud: PointCloud2) -> tuple[Floats, Bytes]:
    """A PointCloud2's finite x, y, z points and colours: its `rgb`/`rgba` field when it has
    one, else a rainbow of `intensity`, else white."""
    fields = {f.name: f for f in cloud.fields}
    missing = [a for a in 'xyz' if a not in fields]
    if missing:
        raise ConvertError(f'the cloud has no {"/".join(missing)} field')
    order = '>' if cloud.is_bigendian else '<'
    names, formats, offsets = [], [], []
    for name, f in fields.items():
        kind = _FIELD_TYPES.get(int(f.datatype))
        if kind is None or not name or int(f.count) != 1:
            continue
        names.append(name)
        formats.append(order + kind)
        offsets.append(int(f.offset))
    step = int(cloud.point_step)
    if (
        step <= 0
        or max(o + np.dtype(t).itemsize for o, t in zip(offsets, formats, strict=False)) > step
    ):
        raise ConvertError(f'point_step {step} is smaller than the fields it holds')
    dtype = np.dtype({'names': names, 'formats': formats, 'offsets': offsets, 'itemsize': step})
    data = np.frombuffer(memoryview(cloud.data).cast('B'), dtype=np.uint8)
    n = len(data) // step
    records = np.frombuffer(data, dtype=dtype, count=n)
    xyz = np.stack([records['x'], records['y'], records['z']], axis=1).astype(np.float32)
    ok = np.isfinite(xyz).all(axis=1)
    colour_field = next((c for c in ('rgb', 'rgba') if c in names), None)
    if colour_field is not None:
        packed = records[colour_field]
        as_int = packed.view(order + 'u4') if packed.dtype.itemsize == 4 else packed.astype('u4')
        colours = np.stack(
            [(as_int >> 16) & 0xFF, (as_int >> 8) & 0xFF, as_int & 0xFF], axis=1
        ).astype(np.uint8)
    elif 'intensity' in names:
        colours = intensity_colours(records['intensity'][ok].astype(np.float32))
        return xyz[ok], colours
    else:
        colours = np.full((n, 3), 255, np.uint8)
    return xyz[ok], colours[ok]


def grid_image(grid: OccupancyGrid) -> Bytes:
    """An OccupancyGrid as RViz's 'map' colour scheme: free white, occupied black, the
    shades of grey between, unknown a blue-grey; row 0 is the grid's first row (y = 0)."""
    info = grid.info
    w, h = int(info.width), int(info.height)
    cells = np.frombuffer(memoryview(grid.data).cast('B'), dtype=np.int8)
    if w * h == 0 or cells.size != w * h:
        raise ConvertError(f'the map holds {cells.size} cells, not {w}x{h}')
    v = cells.reshape(h, w).astype(np.int16)
    grey = (255 - np.clip(v, 0, 100) * 255 // 100).astype(np.uint8)
    img = np.repeat(grey[:, :, None], 3, axis=2)
    img[v < 0] = (112, 137, 134)
    return img


def image_rgb(image: Image) -> Bytes:
    """A sensor_msgs/Image in the encodings cameras send (rgb8, bgr8, rgba8, bgra8, mono8,
    mono16, 16UC1, 32FC1) as an RGB array."""
    enc = str(image.encoding).lower()
    w, h, step = int(image.width), int(image.height), int(image.step)
    raw = np.frombuffer(memoryview(image.data).cast('B'), dtype=np.uint8)
    channels = {
        'rgb8': 3,
        'bgr8': 3,
        'rgba8': 4,
        'bgra8': 4,
        'mono8': 1,
        '8uc1': 1,
        'mono16': 2,
        '16uc1': 2,
        '32fc1': 4,
    }.get(enc)
    if channels is None:
        raise ConvertError(f'image encoding {image.encoding!r} is not drawn')
    if step < w * channels or raw.size < step * h or w * h == 0:
        raise ConvertError(f'the image holds {raw.size} bytes, too few for {w}x{h} {enc}')
    rows = raw[: step * h].reshape(h, step)[:, : w * channels]
    if enc in ('mono16', '16uc1', '32fc1'):
        kind = ('>' if image.is_bigendian else '<') + ('f4' if enc == '32fc1' else 'u2')
        depth = np.ascontiguousarray(rows).view(kind).reshape(h, w).astype(np.float32)
        depth = np.nan_to_num(depth, nan=0.0, posinf=0.0, neginf=0.0)
        top = float(depth.max()) or 1.0
        grey = (depth / top * 255).astype(np.uint8)
        return np.repeat(grey[:, :, None], 3, axis=2)
    px = rows.reshape(h, w, channels)
    if channels == 1:
        return np.repeat(px, 3, axis=2)
    if enc.startswith('bgr'):
        return np.ascontiguousarray(px[:, :, 2::-1])
    return np.ascontiguousarray(px[:, :, :3])


def scaled(image: Bytes, max_width: int) -> Bytes:
    """The image shrunk (every n-th pixel) to at most `max_width` wide, for a slow link."""
    w = image.shape[1]
    if w <= max_width:
        return image
    step = math.ceil(w / max_width)
    return np.ascontiguousarray(image[::step, ::step])


def yaw_quaternion(yaw: float) -> Quat:
    """A rotation about z by `yaw` radians."""
    return (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))


def ground_hit(origin: Vec, direction: Vec) -> tuple[float, float] | None:
    """Where a ray from the camera meets the fixed frame's z = 0 plane (None: it never does)."""
    dz = direction[2]
    if abs(dz) < 1e-9:
        return None
    t = -origin[2] / dz
    if t <= 0:
        return None
    return (origin[0] + t * direction[0], origin[1] + t * direction[1])
