"""A listener as the ROS 2 tf2 tutorial "Writing a listener (Python)" teaches it: spawn
turtle2, then once a second look up where the target frame is as seen from turtle2 and steer
turtle2 towards it."""

import math

import rclpy
from geometry_msgs.msg import Twist
from rclpy.node import Node
from tf2_ros import TransformException
from tf2_ros.buffer import Buffer
from tf2_ros.transform_listener import TransformListener
from turtlesim.srv import Spawn


class FrameListener(Node):
    def __init__(self):
        super().__init__('turtle_tf2_frame_listener')

        # the frame to follow, from the `target_frame` parameter
        self.target_frame = (
            self.declare_parameter('target_frame', 'turtle1').get_parameter_value().string_value
        )

        self.tf_buffer = Buffer()
        self.tf_listener = TransformListener(self.tf_buffer, self)

        # a client of turtlesim's spawn service
        self.spawner = self.create_client(Spawn, 'spawn')
        # whether the spawn service was seen, and whether turtle2 exists yet
        self.turtle_spawning_service_ready = False
        self.turtle_spawned = False

        # turtle2's velocity commands
        self.publisher = self.create_publisher(Twist, 'turtle2/cmd_vel', 1)

        # steer once a second
        self.timer = self.create_timer(1.0, self.on_timer)

    def on_timer(self):
        # the frames between which the transform is looked up
        from_frame_rel = self.target_frame
        to_frame_rel = 'turtle2'

        if self.turtle_spawning_service_ready:
            if self.turtle_spawned:
                # where the target is, seen from turtle2, at the latest time both are known
                try:
                    t = self.tf_buffer.lookup_transform(
                        to_frame_rel, from_frame_rel, rclpy.time.Time()
                    )
                except TransformException as ex:
                    self.get_logger().info(
                        f'Could not transform {to_frame_rel} to {from_frame_rel}: {ex}'
                    )
                    return

                msg = Twist()
                scale_rotation_rate = 1.0
                msg.angular.z = scale_rotation_rate * math.atan2(
                    t.transform.translation.y, t.transform.translation.x
                )

                scale_forward_speed = 0.5
                msg.linear.x = scale_forward_speed * math.sqrt(
                    t.transform.translation.x**2 + t.transform.translation.y**2
                )

                self.publisher.publish(msg)
            else:
                if self.result.done():
                    self.get_logger().info(f'Successfully spawned {self.result.result().name}')
                    self.turtle_spawned = True
                else:
                    self.get_logger().info('Spawn is not finished')
        else:
            if self.spawner.service_is_ready():
                # turtle2 starts at (4, 2), facing along x
                request = Spawn.Request()
                request.name = 'turtle2'
                request.x = float(4)
                request.y = float(2)
                request.theta = float(0)
                self.result = self.spawner.call_async(request)
                self.turtle_spawning_service_ready = True
            else:
                self.get_logger().info('Service is not ready')


def main():
    rclpy.init()
    node = FrameListener()
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass

    rclpy.shutdown()


if __name__ == '__main__':
    main()
