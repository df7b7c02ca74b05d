"""The top-down scene without a network: a tf buffer filled by hand, messages offered as CDR
bytes; where hits, grids, paths, the robot and its outline land, which frame is fixed, and
that a flood keeps one sample a topic."""

from __future__ import annotations

import math
import time

import pytest

from ros2lite.monitor.scene import (
    FRAME_LIMIT,
    TRAIL_POINTS,
    Footprint,
    Scene,
    Snapshot,
    Viewport,
    footprint_from_urdf,
)
from ros2lite.msgs.geometry_msgs.msg import PoseStamped, TransformStamped
from ros2lite.msgs.nav_msgs.msg import OccupancyGrid, Odometry, Path
from ros2lite.msgs.sensor_msgs.msg import LaserScan
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.serialization import serialize_message
from ros2lite.tf2 import BufferCore

SCAN = 'sensor_msgs/msg/LaserScan'


def tf(buffer: BufferCore, parent: str, child: str, x: float, y: float, yaw: float,
       sec: int = 1, static: bool = False) -> None:  # fmt: skip
    t = TransformStamped()
    t.header.frame_id = parent
    t.header.stamp.sec = sec
    t.child_frame_id = child
    t.transform.translation.x = x
    t.transform.translation.y = y
    t.transform.rotation.z = math.sin(yaw / 2)
    t.transform.rotation.w = math.cos(yaw / 2)
    if static:
        buffer.set_transform_static(t, 'test')
    else:
        buffer.set_transform(t, 'test')


def scan(frame: str, ranges: list[float], sec: int = 0) -> bytes:
    msg = LaserScan()
    msg.header.frame_id = frame
    msg.header.stamp.sec = sec
    msg.angle_min = 0.0
    msg.angle_increment = math.pi / 2
    msg.range_min = 0.1
    msg.range_max = 5.0
    msg.ranges = ranges
    return serialize_message(msg)


def close(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
    return all(abs(p - q) < 1e-6 for p, q in zip(a, b, strict=True))


def robot_world() -> BufferCore:
    buffer = BufferCore()
    tf(buffer, 'map', 'odom', 1.0, 0.0, 0.0, static=True)
    tf(buffer, 'odom', 'base_link', 1.0, 2.0, math.pi / 2)
    tf(buffer, 'base_link', 'laser', 0.5, 0.0, 0.0, static=True)
    tf(buffer, 'elsewhere', 'other', 0.0, 0.0, 0.0, static=True)  # a second, smaller tree
    return buffer


def test_hits_and_robot_in_the_root_frame() -> None:
    scene = Scene(robot_world())
    # beams ahead, left, behind (out of range: dropped), right
    scene.offer('/scan', SCAN, scan('laser', [1.0, 2.0, 9.0, float('inf')]))
    snap = scene.snapshot()
    assert snap.fixed_frame == 'map'  # the root of base_link's tree, not of 'elsewhere'
    assert snap.robot is not None and close(snap.robot, (2.0, 2.0, math.pi / 2))
    # the laser is 0.5 m ahead of the robot, which faces +y: at (2, 2.5)
    hits = snap.scans['/scan']
    assert len(hits) == 2
    assert close(hits[0], (2.0, 3.5)) and close(hits[1], (0.0, 2.5))
    names = [name for name, _ in snap.frames]
    assert {'map', 'odom', 'base_link', 'laser'} <= set(names)
    assert snap.bounds() is not None


def test_fixed_and_base_frames_as_asked() -> None:
    scene = Scene(robot_world(), fixed_frame='odom', base_frame='laser')
    snap = scene.snapshot(show_frames=False)
    assert snap.fixed_frame == 'odom' and snap.frames == []
    assert snap.robot is not None and close(snap.robot, (1.0, 2.5, math.pi / 2))
    missing = Scene(robot_world(), fixed_frame='nowhere').snapshot()
    assert missing.robot is None and 'robot: no transform base_link -> nowhere' in missing.problems


def test_a_scan_is_placed_at_its_stamp() -> None:
    buffer = BufferCore()
    tf(buffer, 'odom', 'base_link', 0.0, 0.0, 0.0, sec=1)
    tf(buffer, 'odom', 'base_link', 4.0, 0.0, 0.0, sec=3)
    scene = Scene(buffer)
    scene.offer('/scan', SCAN, scan('base_link', [1.0], sec=2))
    assert close(scene.snapshot().scans['/scan'][0], (3.0, 0.0))  # robot at x=2 at t=2
    scene.offer('/scan', SCAN, scan('base_link', [1.0], sec=9))  # past the buffer: latest
    assert close(scene.snapshot().scans['/scan'][0], (5.0, 0.0))


def test_a_flood_keeps_the_newest_only() -> None:
    scene = Scene(robot_world())
    for k in range(5000):
        scene.offer('/scan', SCAN, scan('laser', [1.0 + k / 10000]))
    scene.offer('/front/scan', SCAN, b'\x00\x01')  # does not decode: shown as nothing
    assert scene.held() == 2
    snap = scene.snapshot()
    assert list(snap.scans) == ['/scan']
    assert close(snap.scans['/scan'][0], (2.0, 2.5 + 1.4999))


def test_grid_path_and_odometry() -> None:
    buffer = BufferCore()
    tf(buffer, 'map', 'odom', 10.0, 0.0, math.pi / 2, static=True)
    scene = Scene(buffer)
    grid = OccupancyGrid()
    grid.header.frame_id = 'odom'
    grid.info.resolution = 0.5
    grid.info.width, grid.info.height = 4, 2
    grid.info.origin.position.x = 1.0
    grid.info.origin.orientation.w = 1.0
    grid.data = [0, 0, 0, 100, -1, 0, 0, 0]
    scene.offer('/map', 'nav_msgs/msg/OccupancyGrid', serialize_message(grid))
    path = Path()
    path.header.frame_id = 'odom'
    path.poses = [PoseStamped(), PoseStamped()]
    path.poses[1].pose.position.x = 1.0
    scene.offer('/plan', 'nav_msgs/msg/Path', serialize_message(path))
    odom = Odometry()
    odom.header.frame_id = 'odom'
    odom.child_frame_id = 'base_link'  # not on tf: the robot is where /odom says
    odom.pose.pose.position.x = 2.0
    odom.pose.pose.orientation.w = 1.0
    scene.offer('/odom', 'nav_msgs/msg/Odometry', serialize_message(odom))
    snap = scene.snapshot()
    assert snap.fixed_frame == 'map'
    (g,) = snap.grids
    # odom is turned a quarter left at (10, 0): odom's (x, y) is the map's (10 - y, x)
    assert g.value_at(10.0 - 0.25, 2.75) == 100  # cell (3, 0): odom (2.75, 0.25)
    assert g.value_at(10.0 - 0.75, 1.25) == -1  # cell (0, 1)
    assert g.value_at(10.0 - 0.25, 1.25) == 0
    assert g.value_at(10.0 + 0.25, 1.25) is None
    assert close(snap.paths['/plan'][1], (10.0, 1.0))
    assert snap.robot is not None and close(snap.robot, (10.0, 2.0, math.pi / 2))


def test_the_trail_is_bounded() -> None:
    buffer = BufferCore()
    scene = Scene(buffer)
    for k in range(TRAIL_POINTS + 50):
        tf(buffer, 'odom', 'base_link', k * 0.05, 0.0, 0.0, sec=k + 1)
        snap = scene.snapshot(show_frames=False)
    assert len(snap.trail) == TRAIL_POINTS and close(
        snap.trail[-1], ((TRAIL_POINTS + 49) * 0.05, 0)
    )


def test_frame_names_that_look_like_yaml() -> None:
    buffer = BufferCore()
    hostile = 'a: b\n- c\x1b[2J'
    tf(buffer, 'map', hostile, 1.0, 0.0, 0.0, static=True)
    snap = Scene(buffer).snapshot()
    assert snap.fixed_frame == 'map'
    assert [name for name, _ in snap.frames] == sorted(['map', hostile])


URDF = """<robot name="r">
  <link name="base_footprint"/>
  <link name="base_link">
    <visual><geometry><cylinder radius="0.3" length="0.1"/></geometry></visual>
    <collision><origin xyz="0.1 0 0" rpy="0 0 1.5707963"/>
      <geometry><box size="0.6 0.4 0.2"/></geometry></collision>
  </link>
  <link name="wheel"><collision><origin rpy="1.5707963 0 0"/>
    <geometry><cylinder radius="0.9" length="0.05"/></geometry></collision></link>
  <joint name="j" type="fixed"><parent link="base_footprint"/><child link="base_link"/>
    <origin xyz="0.2 0 0.1"/></joint>
  <joint name="w" type="continuous"><parent link="base_link"/><child link="wheel"/></joint>
</robot>"""


def test_footprint_from_the_urdf() -> None:
    shape = footprint_from_urdf(URDF, 'base_footprint')
    # the collision box (shapes of collisions win over visuals), behind the fixed joint;
    # the wheel is tilted and on a moving joint: not the outline
    assert shape is not None and (shape.kind, shape.length, shape.width) == ('box', 0.6, 0.4)
    assert close((shape.x, shape.y, shape.yaw), (0.3, 0.0, 1.5707963))
    corners = shape.outline((0.0, 0.0, 0.0))
    assert len(corners) == 5 and all(abs(x - 0.3) <= 0.2 + 1e-6 for x, _ in corners)
    assert footprint_from_urdf('<robot', 'base_link') is None
    assert (
        footprint_from_urdf('<robot name="x"><link name="base_link"/></robot>', 'base_link') is None
    )
    scene = Scene(robot_world())
    assert scene.snapshot().footprint == Footprint(radius=0.2)  # no URDF: the circle
    text = URDF.replace('base_footprint', 'base_link0')  # base_link, on tf, is the root now
    scene.offer('/robot_description', 'std_msgs/msg/String', serialize_message(String(data=text)))
    box = scene.snapshot().footprint
    assert (box.kind, box.x) == ('box', pytest.approx(0.1))


def test_viewport_fits_zooms_and_pans() -> None:
    view = Viewport()
    snap = Snapshot('map', scans={'/s': [(-2.0, -1.0), (2.0, 1.0)]})
    view.update(snap, 100, 100)
    assert (view.cx, view.cy) == (0.0, 0.0)
    left, _ = view.to_dot(-2.0, 0.0, 100, 100)
    assert 0 < left < 10  # the wide side fills the width, with a margin
    x, y = view.to_world(80, 30, 100, 100)
    view.zoom_at(2.0, 80, 30, 100, 100)
    assert close(view.to_world(80, 30, 100, 100), (x, y)) and not view.auto
    view.pan(10, 0)
    assert close(view.to_world(80, 30, 100, 100), (x + 10 * view.scale, y))
    view.update(snap, 100, 100)  # off auto: a new snapshot moves nothing
    assert close(view.to_world(80, 30, 100, 100), (x + 10 * view.scale, y))
    view.follow = True
    view.update(Snapshot('map', robot=(5.0, 6.0, 0.0)), 100, 100)
    assert (view.cx, view.cy) == (5.0, 6.0)


def test_thousands_of_frames_stay_quick() -> None:
    # the tree was read as tf2's YAML: 16 s for 3,000 frames, every half second
    buffer = robot_world()
    for i in range(3000):
        tf(buffer, 'map', f'sensor_{i}', math.cos(i), math.sin(i), 0.0, static=True)
    scene = Scene(buffer)
    started = time.monotonic()
    snap = scene.snapshot()
    assert time.monotonic() - started < 3.0
    # the first FRAME_LIMIT names, less the two of the other tree (not placed in map)
    assert snap.fixed_frame == 'map' and len(snap.frames) == FRAME_LIMIT - 2
    assert f'3006 tf frames: the first {FRAME_LIMIT} drawn' in snap.problems
