"""A scene to look at, published from its own process: TF (map -> odom -> base_link ->
laser), a 360-beam scan, a coloured PointCloud2 and a MarkerArray, each at a known place
and colour so a screenshot can be checked by its pixels."""

from __future__ import annotations

import math
import struct
import sys
import time

import ros2lite
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.msgs.sensor_msgs.msg import LaserScan, PointCloud2, PointField
from ros2lite.msgs.visualization_msgs.msg import Marker, MarkerArray
from ros2lite.node import Node
from ros2lite.qos import QoSProfile, ReliabilityPolicy
from ros2lite.tf2 import StaticTransformBroadcaster, TransformBroadcaster

CLOUD_COLOUR = (0, 0, 255)  # blue points in a square at x -3..-2, y -3..-2 of map
CUBE_COLOUR = (255, 0, 255)  # a magenta cube at (-2, 2) of map


def transform(parent: str, child: str, x: float, y: float, stamp: object) -> TransformStamped:
    t = TransformStamped()
    t.header.frame_id, t.child_frame_id = parent, child
    t.header.stamp = stamp
    t.transform.translation.x, t.transform.translation.y = x, y
    t.transform.rotation.w = 1.0
    return t


def cloud(
    stamp: object,
    n: int,
    corner: tuple[float, float] = (-3.0, -3.0),
    size: float = 1.0,
    frame: str = 'odom',
) -> PointCloud2:
    """`n` points of CLOUD_COLOUR in rows filling a `size` square from `corner` (in `frame`)."""
    msg = PointCloud2()
    msg.header.frame_id, msg.header.stamp = frame, stamp
    msg.fields = [
        PointField(name='x', offset=0, datatype=7, count=1),
        PointField(name='y', offset=4, datatype=7, count=1),
        PointField(name='z', offset=8, datatype=7, count=1),
        PointField(name='rgb', offset=12, datatype=7, count=1),
    ]
    msg.point_step, msg.height, msg.width, msg.is_dense = 16, 1, n, True
    side = max(1, int(math.sqrt(n)))
    rgb = struct.unpack(
        '<f', struct.pack('<I', (CLOUD_COLOUR[0] << 16) | (CLOUD_COLOUR[1] << 8) | CLOUD_COLOUR[2])
    )[0]
    out = bytearray()
    for i in range(n):
        x, y = corner[0] + size * (i % side) / side, corner[1] + size * (i // side) / side
        out += struct.pack('<ffff', x, y, 0.0, rgb)
    msg.row_step = 16 * n
    msg.data = bytes(out)
    return msg


def main() -> None:
    joint = float(sys.argv[1]) if len(sys.argv) > 1 else 0.0
    with ros2lite.init(args=[]):
        node = Node('scene')
        static = StaticTransformBroadcaster(node)
        tf = TransformBroadcaster(node)
        scan_pub = node.create_publisher(
            LaserScan, '/scan', QoSProfile(depth=5, reliability=ReliabilityPolicy.RELIABLE)
        )
        cloud_pub = node.create_publisher(PointCloud2, '/points', 5)
        marker_pub = node.create_publisher(MarkerArray, '/markers', 10)
        static.sendTransform(
            transform('base_link', 'laser', 0.0, 0.0, node.get_clock().now().to_msg())
        )
        big = cloud(node.get_clock().now().to_msg(), 2500)
        while ros2lite.ok():
            now = node.get_clock().now().to_msg()
            tf.sendTransform(
                [
                    transform('map', 'odom', 0.0, 0.0, now),
                    transform('odom', 'base_link', joint, joint, now),
                ]
            )
            scan = LaserScan()
            scan.header.frame_id, scan.header.stamp = 'laser', now
            scan.angle_min, scan.angle_max = -math.pi, math.pi
            scan.angle_increment = 2 * math.pi / 360
            scan.range_min, scan.range_max = 0.1, 30.0
            scan.ranges = [1.5] * 360  # a ring of red points round the laser
            scan_pub.publish(scan)
            big.header.stamp = now
            cloud_pub.publish(big)
            m = Marker()
            m.header.frame_id, m.header.stamp = 'map', now
            m.ns, m.id, m.type, m.action = 'boxes', 1, Marker.CUBE, Marker.ADD
            m.pose.position.x, m.pose.position.y, m.pose.position.z = -2.0, 2.0, 0.5
            m.pose.orientation.w = 1.0
            m.scale.x = m.scale.y = m.scale.z = 1.0
            m.color.r, m.color.g, m.color.b, m.color.a = (*(c / 255 for c in CUBE_COLOUR), 1.0)
            marker_pub.publish(MarkerArray(markers=[m]))
            deadline = time.monotonic() + 0.1
            while time.monotonic() < deadline and ros2lite.ok():
                ros2lite.spin_once(node, timeout_sec=0.02)


if __name__ == '__main__':
    main()
