"""Messages as the arrays the browser draws."""

from __future__ import annotations

import math
import struct

import numpy as np
import pytest

from ros2lite.bundled.rviz2.convert import (
    ConvertError,
    cloud_points,
    decimate,
    grid_image,
    ground_hit,
    image_rgb,
    scan_points,
    wxyz,
)
from ros2lite.msgs.nav_msgs.msg import OccupancyGrid
from ros2lite.msgs.sensor_msgs.msg import Image, LaserScan, PointCloud2, PointField


def test_scan_keeps_valid_returns_only() -> None:
    scan = LaserScan(angle_min=0.0, angle_increment=math.pi / 2, range_min=0.5, range_max=5.0)
    scan.ranges = [1.0, float('inf'), 0.1, 2.0]
    pts = scan_points(scan)
    assert pts.shape == (2, 3)
    assert np.allclose(pts[0], (1, 0, 0)) and np.allclose(pts[1], (0, -2, 0), atol=1e-6)


def test_cloud_rgb_and_nan() -> None:
    fields = [PointField(name=n, offset=4 * i, datatype=7, count=1) for i, n in enumerate('xyz')]
    fields.append(PointField(name='rgb', offset=12, datatype=7, count=1))
    rgb = struct.unpack('<f', struct.pack('<I', 0x10FF20))[0]
    data = struct.pack('<4f', 1, 2, 3, rgb) + struct.pack('<4f', math.nan, 0, 0, rgb)
    cloud = PointCloud2(fields=fields, point_step=16, width=2, height=1, data=data)
    pts, colours = cloud_points(cloud)
    assert pts.tolist() == [[1, 2, 3]] and colours.tolist() == [[0x10, 0xFF, 0x20]]
    with pytest.raises(ConvertError):
        cloud_points(PointCloud2(fields=fields[:2], point_step=16))


def test_decimate_keeps_the_budget() -> None:
    pts, cols = decimate(
        np.zeros((100_000, 3), np.float32), np.zeros((100_000, 3), np.uint8), 30_000
    )
    assert len(pts) <= 30_000 and len(cols) == len(pts)


def test_map_colours_and_image_encodings() -> None:
    grid = OccupancyGrid()
    grid.info.width, grid.info.height = 3, 1
    grid.data = [0, 100, -1]
    assert grid_image(grid)[0].tolist() == [[255] * 3, [0] * 3, [112, 137, 134]]
    img = Image(width=1, height=1, step=3, encoding='bgr8', data=bytes([1, 2, 3]))
    assert image_rgb(img).tolist() == [[[3, 2, 1]]]
    with pytest.raises(ConvertError):
        image_rgb(Image(width=1, height=1, step=3, encoding='yuv422', data=bytes(3)))


def test_ground_hit_and_quaternion() -> None:
    assert ground_hit((0, 0, 2), (0.5, 0, -1)) == (1.0, 0.0)
    assert ground_hit((0, 0, 2), (0, 0, 1)) is None
    assert wxyz((0, 0, 0, 0)) == (1.0, 0.0, 0.0, 0.0)
