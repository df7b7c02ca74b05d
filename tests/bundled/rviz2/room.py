"""A robot in a square room, as real nodes publish it: run as a program, it broadcasts
odom -> base_footprint on /tf (the robot standing at X Y YAW) and the LaserScan of the room's
walls (x and y at +-ROOM_HALF m in odom's frame) from base_footprint, 360 beams at RATE Hz; and,
latched, the room as an OccupancyGrid on /map, a Path on /plan from the robot to PLAN_END, and
a URDF on /robot_description whose base link is a BOX (length, width) behind base_footprint."""

from __future__ import annotations

import contextlib
import math
import sys

ROOM_HALF = 2.0
MAP_RESOLUTION = 0.05
PLAN_END = (-1.0, -1.0)
BOX = (0.5, 0.3)
URDF = f"""<robot name="boxy">
  <link name="base_footprint"/>
  <link name="base_link">
    <visual><geometry><box size="{BOX[0]} {BOX[1]} 0.2"/></geometry></visual>
    <collision><geometry><box size="{BOX[0]} {BOX[1]} 0.2"/></geometry></collision>
  </link>
  <link name="caster"><visual><geometry><sphere radius="0.02"/></geometry></visual></link>
  <joint name="base_joint" type="fixed">
    <parent link="base_footprint"/><child link="base_link"/><origin xyz="0 0 0.1"/>
  </joint>
  <joint name="caster_joint" type="fixed">
    <parent link="base_link"/><child link="caster"/><origin xyz="-0.2 0 -0.1"/>
  </joint>
</robot>
"""


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
    from ros2lite.msgs.geometry_msgs.msg import PoseStamped, TransformStamped
    from ros2lite.msgs.nav_msgs.msg import OccupancyGrid, Path
    from ros2lite.msgs.sensor_msgs.msg import LaserScan
    from ros2lite.msgs.std_msgs.msg import String
    from ros2lite.qos import DurabilityPolicy, QoSProfile
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
        t.child_frame_id = 'base_footprint'
        t.transform.translation.x = x
        t.transform.translation.y = y
        t.transform.rotation.z = math.sin(yaw / 2)
        t.transform.rotation.w = math.cos(yaw / 2)
        tf.sendTransform(t)
        scan = LaserScan()
        scan.header.stamp = now
        scan.header.frame_id = 'base_footprint'
        scan.angle_min = 0.0
        scan.angle_increment = 2 * math.pi / len(beams)
        scan.angle_max = scan.angle_increment * (len(beams) - 1)
        scan.range_min = 0.1
        scan.range_max = 10.0
        scan.ranges = beams
        scans.publish(scan)

    latched = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    grid = OccupancyGrid()
    grid.header.frame_id = 'odom'
    cells = round(2 * ROOM_HALF / MAP_RESOLUTION) + 2  # the walls' cells just outside
    grid.info.resolution = MAP_RESOLUTION
    grid.info.width = grid.info.height = cells
    grid.info.origin.position.x = grid.info.origin.position.y = -ROOM_HALF - MAP_RESOLUTION
    grid.info.origin.orientation.w = 1.0
    grid.data = [
        100 if i in (0, cells - 1) or j in (0, cells - 1) else 0
        for j in range(cells)
        for i in range(cells)
    ]
    node.create_publisher(OccupancyGrid, '/map', latched).publish(grid)
    plan = Path()
    plan.header.frame_id = 'odom'
    for k in range(11):
        pose = PoseStamped()
        pose.header.frame_id = 'odom'
        pose.pose.position.x = x + (PLAN_END[0] - x) * k / 10
        pose.pose.position.y = y + (PLAN_END[1] - y) * k / 10
        plan.poses.append(pose)
    node.create_publisher(Path, '/plan', latched).publish(plan)
    node.create_publisher(String, '/robot_description', latched).publish(String(data=URDF))
    node.create_timer(1.0 / rate, tick)
    print('room up', flush=True)
    with contextlib.suppress(KeyboardInterrupt, ExternalShutdownException):
        ros2lite.spin(node)


if __name__ == '__main__':
    main()
