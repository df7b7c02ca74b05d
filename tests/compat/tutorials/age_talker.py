"""Publishes a message of a package of the user's own (`my_interfaces/msg/Age`)."""

import rclpy
from my_interfaces.msg import Age
from rclpy.node import Node


class AgePublisher(Node):
    def __init__(self):
        super().__init__('age_publisher')
        self.pub = self.create_publisher(Age, 'age', 10)
        self.create_timer(0.2, lambda: self.pub.publish(Age(years=7, name='ros2lite')))


def main():
    rclpy.init()
    try:
        rclpy.spin(AgePublisher())
    except KeyboardInterrupt:
        pass


if __name__ == '__main__':
    main()
