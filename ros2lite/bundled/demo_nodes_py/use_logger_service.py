"""`use_logger_service`: a node's logger level changed from outside through its logger
services. `LoggerServiceNode` (logger services on) logs each `std_msgs/String` on `output` at
DEBUG, INFO, WARN and ERROR; `TestNode` sends it a message, reads its level, and sets it to
DEBUG, WARN and ERROR in turn, sending a message at each, so what gets through shows the
level at work."""

from __future__ import annotations

import threading

import ros2lite
from ros2lite.bundled.runner import run_main
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.logging import LoggingSeverity
from ros2lite.msgs.rcl_interfaces.msg import LoggerLevel
from ros2lite.msgs.rcl_interfaces.srv import GetLoggerLevels, SetLoggerLevels
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node

SETTLE = 5.0  # how long a published message may take to be logged before the next step


class LoggerServiceNode(Node):
    """Logs every message on `output` at four levels; its level is set from outside."""

    def __init__(self) -> None:
        super().__init__('LoggerServiceNode', enable_logger_service=True)
        self.sub = self.create_subscription(String, 'output', self.callback, 10)
        self.handled = threading.Event()  # set once a message has been logged

    def callback(self, msg: String) -> None:
        """Say it at each level; the logger's level decides which lines appear."""
        logger = self.get_logger()
        logger.debug(msg.data + ' with DEBUG logger level.')
        logger.info(msg.data + ' with INFO logger level.')
        logger.warn(msg.data + ' with WARN logger level.')
        logger.error(msg.data + ' with ERROR logger level.')
        self.handled.set()


class TestNode(Node):
    """Publishes on `output` and calls the other node's logger services."""

    def __init__(self, remote_node_name: str, handled: threading.Event) -> None:
        super().__init__('TestNode')
        self.handled = handled
        self.pub = self.create_publisher(String, 'output', 10)
        self.get_client = self.create_client(
            GetLoggerLevels, remote_node_name + '/get_logger_levels'
        )
        self.set_client = self.create_client(
            SetLoggerLevels, remote_node_name + '/set_logger_levels'
        )
        self.remote_node_name = remote_node_name

    def set_remote_level(self, level: int) -> bool:
        """Set the remote node's level; False when the service is not there or refuses."""
        if not self.set_client.service_is_ready():
            return False
        request = SetLoggerLevels.Request(
            levels=[LoggerLevel(name=self.remote_node_name, level=level)]
        )
        future = self.set_client.call_async(request)
        ros2lite.spin_until_future_complete(self, future)
        response = future.result()
        if not response:
            return False
        if not response.results[0].successful:
            self.get_logger().error('Failed to change logger level: ' + response.results[0].reason)
            return False
        return True

    def get_remote_level(self) -> int | None:
        """The remote node's level, or None when the service did not answer."""
        if not self.get_client.service_is_ready():
            return None
        future = self.get_client.call_async(GetLoggerLevels.Request(names=[self.remote_node_name]))
        ros2lite.spin_until_future_complete(self, future)
        response = future.result()
        return response.levels[0].level if response else None

    def log_remote_level(self) -> None:
        """Log the level the remote node reports."""
        level = self.get_remote_level()
        if level is None:
            self.get_logger().error('Failed to get logger level via logger service !')
        else:
            self.get_logger().info(f'Current logger level: {level}')

    def send(self, text: str) -> None:
        """Publish `text` and wait until it has been logged (ROS's demo sleeps half a
        second instead, which a busy machine can outrun)."""
        self.handled.clear()
        self.pub.publish(String(data=text))
        self.handled.wait(SETTLE)


def walk_through() -> None:
    """Default level, then DEBUG, WARN and ERROR, a message and a level read at each."""
    service_node = LoggerServiceNode()
    test_node = TestNode('LoggerServiceNode', service_node.handled)
    executor = SingleThreadedExecutor()
    executor.add_node(service_node)
    thread = threading.Thread(target=executor.spin, daemon=True)
    thread.start()
    try:
        # the services are a step away in the graph; half a second of ROS's sleeps hid that
        for client in (test_node.get_client, test_node.set_client):
            client.wait_for_service(timeout_sec=SETTLE)
        test_node.get_logger().info('Output with default logger level:')
        test_node.send('Output 1')
        test_node.log_remote_level()
        steps = [('debug', LoggingSeverity.DEBUG), ('warn', LoggingSeverity.WARN)]
        steps.append(('error', LoggingSeverity.ERROR))
        for number, (name, level) in enumerate(steps, start=2):
            test_node.get_logger().info(f'Output with {name} logger level:')
            if test_node.set_remote_level(level):
                test_node.send(f'Output {number}')
            else:
                test_node.get_logger().error(
                    f'Failed to set {name} logger level via logger service !'
                )
            test_node.log_remote_level()
    finally:
        executor.shutdown()
        thread.join()
        ros2lite.try_shutdown()


def main(args: list[str] | None = None) -> int:
    """`use_logger_service`'s entry point."""
    return run_main(walk_through, args)


if __name__ == '__main__':
    raise SystemExit(main())
