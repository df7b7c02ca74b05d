"""A robot in a square room, as real nodes publish it: run as a program, it broadcasts
odom -> base_link on /tf (the robot standing at X Y YAW) and the LaserScan of the room's walls
(x and y at +-HALF metres in odom's frame) from base_link, 360 beams at RATE Hz."""

from __future__ import annotations

import contextlib
import math
import sys

ROOM_HALF = 2.0


def ranges(x: float, y: float, yaw: float, beams: int = 360) -> list[float]:
    """What a laser at (x, y) facing yaw measures to the walls of the room."""
    out = []
    for k in range(beams):
        theta = yaw + 2 * math.pi * k / beams
        c, s = math.cos(theta), math.sin(theta)
        best = math.inf
        for wall, d in ((ROOM_HALF - x, c), (-ROOM_HALF - x, c), (ROOM_HALF - y, s),
                        (-ROOM_HALF - y, s)):  # fmt: skip
            if abs(d) > 1e-9 and wall / d > 0:
                best = min(best, wall / d)
        out.append(best)
    return out


def main() -> None:
    import ros2lite
    from ros2lite.executors import ExternalShutdownException
    from ros2lite.msgs.geometry_msgs.msg import TransformStamped
    from ros2lite.msgs.sensor_msgs.msg import LaserScan
    from ros2lite.tf2 import TransformBroadcaster

    x, y, yaw, rate = (float(v) for v in sys.argv[1:5])
    ros2lite.init()
    node = ros2lite.create_node('square_room')
    tf = TransformBroadcaster(node)
    scans = node.create_publisher(LaserScan, '/scan', 10)
    beams = ranges(x, y, yaw)

    def tick() -> None:
        now = node.get_clock().now().to_msg()
        t = TransformStamped()
        t.header.stamp = now
        t.header.frame_id = 'odom'
        t.child_frame_id = 'base_link'
        t.transform.translation.x = x
        t.transform.translation.y = y
        t.transform.rotation.z = math.sin(yaw / 2)
        t.transform.rotation.w = math.cos(yaw / 2)
        tf.sendTransform(t)
        scan = LaserScan()
        scan.header.stamp = now
        scan.header.frame_id = 'base_link'
        scan.angle_min = 0.0
        scan.angle_increment = 2 * math.pi / len(beams)
        scan.angle_max = scan.angle_increment * (len(beams) - 1)
        scan.range_min = 0.1
        scan.range_max = 10.0
        scan.ranges = beams
        scans.publish(scan)

    node.create_timer(1.0 / rate, tick)
    print('room up', flush=True)
    with contextlib.suppress(KeyboardInterrupt, ExternalShutdownException):
        ros2lite.spin(node)


if __name__ == '__main__':
    main()
