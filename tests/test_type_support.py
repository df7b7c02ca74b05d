"""What a user's type checker sees: mypy on a script written the rclpy way, against the
library and its generated message stubs."""

from __future__ import annotations

import os
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

USER_SCRIPT = '''
from __future__ import annotations

import ros2lite
from ros2lite.action import ActionClient, ActionServer, ServerGoalHandle
from ros2lite.msgs.action_tutorials_interfaces.action import Fibonacci
from ros2lite.msgs.example_interfaces.srv import AddTwoInts
from ros2lite.msgs.geometry_msgs.msg import Twist
from ros2lite.msgs.sensor_msgs.msg import Image
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node


class Talker(Node):
    def __init__(self) -> None:
        super().__init__('talker')
        self.pub = self.create_publisher(String, 'chatter', 10)
        reveal_type(self.pub)  # publisher
        self.sub = self.create_subscription(String, 'chatter', self.on_message, 10)
        reveal_type(self.sub)  # subscription
        self.twist = self.create_subscription(Twist, 'cmd_vel', lambda m: m.linear.x, 10)
        reveal_type(self.twist)  # lambda subscription
        self.srv = self.create_service(AddTwoInts, 'add_two_ints', self.add)
        reveal_type(self.srv)  # service
        self.create_timer(1.0, self.tick)

    def tick(self) -> None:
        msg = String(data='hello')
        reveal_type(msg.data)  # field
        self.pub.publish(msg)

    def on_message(self, msg: String) -> None:
        self.get_logger().info(msg.data)

    def add(
        self, request: AddTwoInts.Request, response: AddTwoInts.Response
    ) -> AddTwoInts.Response:
        response.sum = request.a + request.b
        return response


def execute(
    goal_handle: ServerGoalHandle[Fibonacci.Goal, Fibonacci.Result, Fibonacci.Feedback],
) -> Fibonacci.Result:
    goal_handle.publish_feedback(Fibonacci.Feedback(partial_sequence=[0, 1]))
    goal_handle.succeed()
    return Fibonacci.Result(sequence=[0, 1, 1])


def main() -> None:
    context = ros2lite.init()
    reveal_type(context)  # context
    node = Talker()
    client = node.create_client(AddTwoInts, 'add_two_ints')
    reveal_type(client)  # client
    response = client.call(AddTwoInts.Request(a=1, b=2))
    reveal_type(response)  # call
    reveal_type(client.call_async(AddTwoInts.Request(a=1, b=2)))  # call_async
    reveal_type(Image().data)  # uint8 array
    reveal_type(Image().header.stamp.sec)  # nested field
    loose = node.create_publisher('std_msgs/msg/String', 'loose', 10)
    reveal_type(loose)  # by name
    server = ActionServer(node, Fibonacci, 'fibonacci', execute)
    reveal_type(server)  # action server
    goals = ActionClient(node, Fibonacci, 'fibonacci')
    result = goals.send_goal(Fibonacci.Goal(order=5))
    if result is not None:
        reveal_type(result.result.sequence)  # action result
    ros2lite.shutdown()
'''

MISTAKES = '''
from ros2lite.msgs.example_interfaces.srv import AddTwoInts
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node

node = Node('mistakes')
msg = String()
msg.data = 5  # wrong field type
String(data=5)  # wrong keyword type
msg.dta = 'x'  # misspelt field
node.create_publisher(String, 'chatter', 10).publish(AddTwoInts.Request())  # wrong message
node.create_client(AddTwoInts, 'add_two_ints').call(String())  # wrong request
node.create_subscription(String, 'chatter', lambda m: m.dta, 10)  # misspelt in a callback
'''

EXPECTED_TYPES = {
    'publisher': 'ros2lite.publisher.Publisher[ros2lite.msgs.std_msgs.msg.String]',
    'subscription': 'ros2lite.subscription.Subscription[ros2lite.msgs.std_msgs.msg.String]',
    'lambda subscription': (
        'ros2lite.subscription.Subscription[ros2lite.msgs.geometry_msgs.msg.Twist]'
    ),
    'service': (
        'ros2lite.service.Service[ros2lite.msgs.example_interfaces.srv.AddTwoInts_Request, '
        'ros2lite.msgs.example_interfaces.srv.AddTwoInts_Response]'
    ),
    'field': 'str',
    'context': 'ros2lite.context.Context',
    'client': (
        'ros2lite.client.Client[ros2lite.msgs.example_interfaces.srv.AddTwoInts_Request, '
        'ros2lite.msgs.example_interfaces.srv.AddTwoInts_Response]'
    ),
    'call': 'ros2lite.msgs.example_interfaces.srv.AddTwoInts_Response',
    'call_async': (
        'ros2lite.task.Future[ros2lite.msgs.example_interfaces.srv.AddTwoInts_Response]'
    ),
    'uint8 array': 'array.array[int]',
    'nested field': 'int',
    'by name': 'ros2lite.publisher.Publisher[Any]',
    'action server': (
        'ros2lite.action.server.ActionServer['
        'ros2lite.msgs.action_tutorials_interfaces.action.Fibonacci_Goal, '
        'ros2lite.msgs.action_tutorials_interfaces.action.Fibonacci_Result, '
        'ros2lite.msgs.action_tutorials_interfaces.action.Fibonacci_Feedback]'
    ),
    'action result': 'array.array[int]',
}


def _mypy(tmp_path: Path, name: str, source: str) -> tuple[str, list[str]]:
    """Run mypy as a user would on `source`, with ros2lite found as an installed, typed
    package (its own modules are not reported on, as with anything in site-packages)."""
    script = tmp_path / name
    script.write_text(textwrap.dedent(source).lstrip())
    config = tmp_path / 'mypy.ini'
    config.write_text('[mypy]\nstrict = True\n\n[mypy-ros2lite.*]\nfollow_imports = silent\n')
    env = {**os.environ, 'MYPYPATH': str(ROOT)}
    proc = subprocess.run(
        [
            sys.executable,
            '-m',
            'mypy',
            '--config-file',
            str(config),
            '--cache-dir',
            str(tmp_path / '.mypy_cache'),
            '--show-absolute-path',
            '--no-pretty',
            '--no-error-summary',
            str(script),
        ],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
        timeout=240,
    )
    assert proc.stderr == '', proc.stderr
    return script.read_text(), proc.stdout.splitlines()


@pytest.fixture(scope='module')
def checked(tmp_path_factory: pytest.TempPathFactory) -> tuple[str, list[str]]:
    return _mypy(tmp_path_factory.mktemp('typed'), 'talker.py', USER_SCRIPT)


def test_a_script_written_the_rclpy_way_type_checks(checked: tuple[str, list[str]]) -> None:
    _, lines = checked
    errors = [line for line in lines if ': error:' in line]
    assert errors == []


def test_mypy_sees_the_types_of_entities_messages_and_responses(
    checked: tuple[str, list[str]],
) -> None:
    source, lines = checked
    labels = {
        number: line.split('# ', 1)[1]
        for number, line in enumerate(source.splitlines(), 1)
        if 'reveal_type(' in line
    }
    revealed = {}
    for line in lines:
        m = re.match(r'.*:(\d+): note: Revealed type is "(.*)"$', line)
        if m:
            revealed[labels[int(m[1])]] = m[2]
    assert revealed == EXPECTED_TYPES


def test_mypy_reports_wrong_field_types_and_mismatched_messages(tmp_path: Path) -> None:
    source, lines = _mypy(tmp_path, 'mistakes.py', MISTAKES)
    flagged = {int(m[1]) for line in lines if (m := re.match(r'.*:(\d+): error:', line))}
    wanted = {n for n, line in enumerate(source.splitlines(), 1) if '  # ' in line}
    assert flagged == wanted, '\n'.join(lines)
    assert any('variable has type "str"' in line for line in lines)
