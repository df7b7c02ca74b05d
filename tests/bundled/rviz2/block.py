"""A block of blue points to decimate, published from its own process: a PointCloud2 of N
points (argv[1]) filling the 2 m square round the origin of frame `block`, twice a second;
`block` is at (-2, 2) of map (a static transform), so the block is drawn where TF puts it,
left of map's origin on the screen."""

from __future__ import annotations

import sys
import time

import ros2lite
from ros2lite.msgs.sensor_msgs.msg import PointCloud2
from ros2lite.node import Node
from ros2lite.tf2 import StaticTransformBroadcaster
from tests.bundled.rviz2.scene import cloud, transform

TOPIC = '/block'
FRAME = 'block'
AT = (-2.0, 2.0)  # where FRAME is in map


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 20_000
    with ros2lite.init(args=[]):
        node = Node('block')
        pub = node.create_publisher(PointCloud2, TOPIC, 5)
        now = node.get_clock().now().to_msg()
        StaticTransformBroadcaster(node).sendTransform(transform('map', FRAME, *AT, now))
        msg = cloud(now, n, corner=(-1.0, -1.0), size=2.0, frame=FRAME)
        while ros2lite.ok():
            msg.header.stamp = node.get_clock().now().to_msg()
            pub.publish(msg)
            time.sleep(0.5)


if __name__ == '__main__':
    main()
