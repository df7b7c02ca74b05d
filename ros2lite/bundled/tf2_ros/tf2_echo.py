"""`tf2_echo SOURCE TARGET [RATE]`: prints the transform between two frames, RATE times a
second (1 by default), in tf2_ros's tf2_echo layout: the time, translation, rotation as a
quaternion and as roll/pitch/yaw in radians and degrees, and the 4x4 matrix.

As in tf2_ros, the transform printed is `lookup_transform(SOURCE, TARGET)`: TARGET's pose in
SOURCE's frame, i.e. what takes data from TARGET into SOURCE.
"""

from __future__ import annotations

import math
import sys
from typing import TYPE_CHECKING

from ros2lite.bundled.display import own_arguments
from ros2lite.bundled.runner import run_node
from ros2lite.bundled.tf2_ros.static_transform_publisher import C_FLOAT
from ros2lite.node import Node
from ros2lite.tf2 import Buffer, TransformException, TransformListener
from ros2lite.tf2.math import matrix_from_quaternion, rpy_from_matrix
from ros2lite.time import Time

if TYPE_CHECKING:
    from ros2lite.msgs.geometry_msgs.msg import TransformStamped

USAGE = (
    'Usage: tf2_echo source_frame target_frame [echo_rate]\n\n'
    'This will echo the transform from the coordinate frame of the source_frame\n'
    'to the coordinate frame of the target_frame. \n'
    'Note: This is the transform to get data from target_frame into the source_frame.\n'
    'Default echo rate is 1 if echo_rate is not given.\n'
)


def format_transform(t: TransformStamped) -> str:
    """The block tf2_echo prints for one transform (fixed, 3 decimals)."""
    tr, r = t.transform.translation, t.transform.rotation
    m = matrix_from_quaternion((r.x, r.y, r.z, r.w))
    roll, pitch, yaw = rpy_from_matrix(m)
    deg = 180.0 / math.pi
    xyz = (tr.x, tr.y, tr.z)
    lines = [
        f'At time {t.header.stamp.sec}.{t.header.stamp.nanosec}',
        f'- Translation: [{tr.x:.3f}, {tr.y:.3f}, {tr.z:.3f}]',
        f'- Rotation: in Quaternion [{r.x:.3f}, {r.y:.3f}, {r.z:.3f}, {r.w:.3f}]',
        f'- Rotation: in RPY (radian) [{roll:.3f}, {pitch:.3f}, {yaw:.3f}]',
        f'- Rotation: in RPY (degree) [{roll * deg:.3f}, {pitch * deg:.3f}, {yaw * deg:.3f}]',
        '- Matrix:',
    ]
    for i in range(3):
        lines.append(''.join(f' {v:6.3f}' for v in (*m[i], xyz[i])))
    lines.append(''.join(f' {v:6.3f}' for v in (0.0, 0.0, 0.0, 1.0)))
    return '\n'.join(lines) + '\n'


class Tf2Echo(Node):
    """Waits until the frames connect, then prints their transform on every tick."""

    def __init__(self, source: str, target: str, rate: float) -> None:
        super().__init__('tf2_echo')
        self.source, self.target = source, target
        self.buffer = Buffer()
        self.listener = TransformListener(self.buffer, self, spin_thread=True)
        self.ready = False
        self.fixed_format = False  # C++ streams print plain doubles until the first echo
        self.timer = self.create_timer(1.0 / rate, self.tick)
        self.tick()

    def tick(self) -> None:
        """Wait (saying why, once a second) or print the transform."""
        if not self.ready:
            ok, why = self.buffer.can_transform_core(self.source, self.target, Time())
            if not ok:
                self.get_logger().info(
                    f'Waiting for transform {self.source} ->  {self.target}: {why}',
                    throttle_duration_sec=1.0,
                )
                return
            self.ready = True
        try:
            t = self.buffer.lookup_transform(self.source, self.target, Time())
        except TransformException as e:
            now = self.get_clock().now().nanoseconds / 1e9
            text = f'{now:.3f}' if self.fixed_format else f'{now:g}'
            print(
                f'Failure at {text}\nException thrown:{e}\nThe current list of frames is:\n'
                f'{self.buffer.all_frames_as_string()}',
                flush=True,
            )
            return
        self.fixed_format = True
        print(format_transform(t), end='', flush=True)


def _rate(text: str) -> float | int:
    """The rate argument as std::stof reads it; an exit status (2: no number, 3: junk after
    the number) when it is not one."""
    match = C_FLOAT.match(text)
    if match is None:
        return 2
    if match.end() != len(text):
        return 3
    return float(match.group(0))


def main(args: list[str] | None = None) -> int:
    """`tf2_echo`'s entry point."""
    argv = own_arguments(args)
    if len(argv) not in (2, 3):
        print(USAGE, end='', flush=True)
        return 1
    rate = 1.0
    if len(argv) == 3:
        parsed = _rate(argv[2])
        if isinstance(parsed, int):
            print(
                f"Failed to convert rate argument '{argv[2]}' to a floating-point number",
                file=sys.stderr,
            )
            return parsed
        if not parsed > 0 or math.isinf(parsed):
            print(f"The echo rate must be a positive number, not '{argv[2]}'", file=sys.stderr)
            return 2
        rate = parsed
    source, target = argv[0], argv[1]
    return run_node(lambda: Tf2Echo(source, target, rate), args)


if __name__ == '__main__':
    sys.exit(main())
