"""The README lesson with code as the ROS tutorials write it (`import rclpy`, `from
std_msgs.msg import String`, a custom message package), unbuilt: run and launch.

It needs ros2lite's `rclpy` face in the compat directory (`ros2lite env`); without it the
test says so and skips — the same workflow with ros2lite's own API is tested in
tests/cli/test_run.py.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from ros2lite.pkg.environment import COMPAT_DIR
from tests.cli.conftest import run_process
from tests.cli.test_launch import Launch

pytestmark = pytest.mark.skipif(
    not (COMPAT_DIR / 'rclpy' / '__init__.py').is_file(),
    reason="needs ros2lite's rclpy face (ros2lite/compat/rclpy)",
)

PUBLISHER = '''
import rclpy
from rclpy.node import Node

from std_msgs.msg import String
from tutorial_interfaces.msg import Age


class MinimalPublisher(Node):

    def __init__(self):
        super().__init__('minimal_publisher')
        self.publisher_ = self.create_publisher(String, 'topic', 10)
        self.ages = self.create_publisher(Age, 'age', 10)
        timer_period = 0.5  # seconds
        self.timer = self.create_timer(timer_period, self.timer_callback)
        self.i = 0

    def timer_callback(self):
        msg = String()
        msg.data = 'Hello World: %d' % self.i
        self.publisher_.publish(msg)
        self.ages.publish(Age(years=self.i, months=1))
        self.get_logger().info('Publishing: "%s"' % msg.data)
        self.i += 1


def main(args=None):
    rclpy.init(args=args)
    minimal_publisher = MinimalPublisher()
    rclpy.spin(minimal_publisher)
    minimal_publisher.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
'''

SUBSCRIBER = '''
import rclpy
from rclpy.node import Node

from std_msgs.msg import String


class MinimalSubscriber(Node):

    def __init__(self):
        super().__init__('minimal_subscriber')
        self.subscription = self.create_subscription(
            String,
            'topic',
            self.listener_callback,
            10)
        self.subscription  # prevent unused variable warning

    def listener_callback(self, msg):
        self.get_logger().info('I heard: "%s"' % msg.data)


def main(args=None):
    rclpy.init(args=args)
    minimal_subscriber = MinimalSubscriber()
    rclpy.spin(minimal_subscriber)
    minimal_subscriber.destroy_node()
    rclpy.shutdown()


if __name__ == '__main__':
    main()
'''

LAUNCH = '''
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(package='py_pubsub', executable='talker', output='screen'),
        Node(package='py_pubsub', executable='listener', output='screen'),
    ])
'''


@pytest.fixture
def lesson(tmp_path: Path) -> Path:
    """The lesson's workspace, as the student leaves it: two packages, no build."""
    src = tmp_path / 'ros2_ws' / 'src'
    src.mkdir(parents=True)
    for args in (
        ['--build-type', 'ament_cmake', 'tutorial_interfaces'],
        [
            '--build-type',
            'ament_python',
            'py_pubsub',
            '--dependencies',
            'rclpy',
            'std_msgs',
            'tutorial_interfaces',
        ],
    ):
        result = run_process(
            'pkg', 'create', '--license', 'Apache-2.0', '--destination-directory', str(src), *args
        )
        assert result.code == 0, result.err
    (src / 'tutorial_interfaces' / 'msg').mkdir()
    (src / 'tutorial_interfaces' / 'msg' / 'Age.msg').write_text('uint8 years\nuint8 months\n')
    pkg = src / 'py_pubsub'
    (pkg / 'py_pubsub' / 'publisher_member_function.py').write_text(PUBLISHER)
    (pkg / 'py_pubsub' / 'subscriber_member_function.py').write_text(SUBSCRIBER)
    (pkg / 'launch').mkdir()
    (pkg / 'launch' / 'pubsub.launch.py').write_text(LAUNCH)
    setup = pkg / 'setup.py'
    setup.write_text(
        setup.read_text().replace(
            "'console_scripts': [\n",
            "'console_scripts': [\n"
            "            'talker = py_pubsub.publisher_member_function:main',\n"
            "            'listener = py_pubsub.subscriber_member_function:main',\n",
        )
    )
    return tmp_path / 'ros2_ws'


def test_run_and_launch_the_tutorial_code(lesson: Path, processes: Any) -> None:
    proc = processes.start(
        [sys.executable, '-m', 'ros2lite', 'launch', 'py_pubsub', 'pubsub.launch.py'],
        stdin=subprocess.DEVNULL,
        stderr=subprocess.STDOUT,
        start_new_session=True,
        cwd=lesson,
    )
    launch = Launch(proc)
    launch.wait_for('I heard: "Hello World: 1"')
    echo = processes.start(
        [sys.executable, '-m', 'ros2lite', 'topic', 'echo', '--once', '/age'],
        stdin=subprocess.DEVNULL,
        cwd=lesson,
    )
    out, err = echo.communicate(timeout=30)
    assert out.startswith('years: ') and 'months: 1' in out, err
    running = list(launch.lines)
    assert not any('Traceback' in line for line in running), running
    # the tutorial's main() does not catch Ctrl-C: as with rclpy, each node may show a
    # KeyboardInterrupt traceback; the launch still stops both and ends cleanly
    assert launch.interrupt() == 0
    for label in ('talker-1', 'listener-2'):
        assert any(f'[{label}]: process has' in line for line in launch.lines), launch.lines
