"""An obstacle-avoidance exercise as the TurtleBot3 courses write it, with plain rclpy: read
/scan, drive forward while the way ahead is clear, turn away from the nearer side otherwise.
It stops itself after `run_for` seconds of sim time and prints how far it drove."""

import contextlib
import math
import sys

import rclpy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rclpy.node import Node
from rclpy.qos import qos_profile_sensor_data
from sensor_msgs.msg import LaserScan


class ObstacleAvoider(Node):
    def __init__(self, run_for):
        super().__init__('obstacle_avoider')
        self.run_for = run_for
        self.scan = None
        self.travelled = 0.0
        self.last = None
        self.start = None
        self.turn = 0.0
        self.pub = self.create_publisher(Twist, 'cmd_vel', 10)
        self.create_subscription(LaserScan, 'scan', self.on_scan, qos_profile_sensor_data)
        self.create_subscription(Odometry, 'odom', self.on_odom, 10)
        self.timer = self.create_timer(0.1, self.on_timer)

    def on_scan(self, msg):
        self.scan = msg

    def on_odom(self, msg):
        p = msg.pose.pose.position
        if self.last is not None:
            self.travelled += math.hypot(p.x - self.last[0], p.y - self.last[1])
        self.last = (p.x, p.y)

    def sector(self, lo, hi):
        values = [self.scan.ranges[i % 360] for i in range(lo, hi)]
        finite = [v for v in values if math.isfinite(v) and v > 0.0]
        return min(finite) if finite else float('inf')

    def on_timer(self):
        now = self.get_clock().now().nanoseconds / 1e9
        if self.start is None:
            self.start = now
        if now - self.start >= self.run_for:
            self.pub.publish(Twist())
            print(f'done: {now - self.start:.1f} s, travelled {self.travelled:.2f} m', flush=True)
            raise SystemExit(0)
        if self.scan is None:
            return
        cmd = Twist()
        if self.sector(-35, 36) > 0.5:
            cmd.linear.x = 0.2
            self.turn = 0.0
        else:
            # keep turning the way it started until the way ahead is clear
            if not self.turn:
                left, right = self.sector(35, 100), self.sector(260, 325)
                self.turn = 1.0 if left > right else -1.0
            cmd.angular.z = self.turn
        self.pub.publish(cmd)


def main():
    rclpy.init()
    node = ObstacleAvoider(float(sys.argv[1]))
    node.set_parameters([rclpy.parameter.Parameter('use_sim_time', value=True)])
    with contextlib.suppress(SystemExit):
        rclpy.spin(node)
    rclpy.shutdown()


if __name__ == '__main__':
    main()
