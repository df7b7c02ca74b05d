"""`--json` of the data verbs (issue 37 item 1), read with `jq` as a script would, against one
real node process (a test_msgs publisher, a service, an action server, parameters) that every
test here shares."""

from __future__ import annotations

import base64
import json
import os
import shutil
import subprocess
import sys
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from tests.cli.conftest import Result
from tests.spinning import wait_until

pytestmark = pytest.mark.skipif(shutil.which('jq') is None, reason='needs jq')

DATA = str(Path(__file__).parents[1] / 'interfaces' / 'data')  # test_msgs definitions
NODE = '/json/graph'
UNBOUNDED = 'test_msgs/msg/UnboundedSequences'

GRAPH_CODE = """
import math, sys
import ros2lite
from ros2lite.action import ActionServer
from ros2lite.interfaces import get_interface
from ros2lite.node import Node

Seq = get_interface('test_msgs/msg/UnboundedSequences')
Basic = get_interface('test_msgs/msg/BasicTypes')
Fib = get_interface('example_interfaces/action/Fibonacci')
Add = get_interface('example_interfaces/srv/AddTwoInts')

def sample():
    m = Seq()
    m.byte_values = [b'\\x00', b'\\xff']
    m.uint8_values = bytes(range(256))
    m.char_values = [65, 66]
    m.float32_values = [1.5, math.nan, -math.inf]
    m.float64_values = [1e-07, math.inf, -0.0]
    m.int64_values = [-(2**63), 2**53 + 1]
    m.uint64_values = [2**64 - 1]
    m.string_values = ['ünï', '"q"', '']
    m.basic_types_values = [Basic(float64_value=math.nan, byte_value=b'\\x07', char_value=9)]
    return m

def add(req, res):
    res.sum = req.a + req.b
    return res

def fib(handle):
    seq = [0, 1]
    for _ in range(handle.request.order - 1):
        seq.append(seq[-1] + seq[-2])
        handle.publish_feedback(Fib.Feedback(sequence=seq))
    handle.succeed()
    return Fib.Result(sequence=seq)

with ros2lite.init(args=sys.argv):
    node = Node('graph', namespace='/json')
    pub = node.create_publisher(Seq, '/json/seq', 10)
    node.create_timer(0.05, lambda: pub.publish(sample()))
    node.create_service(Add, '/json/add', add)
    ActionServer(node, Fib, '/json/fib', fib)
    node.declare_parameter('ratio', 1.5)
    node.declare_parameter('names', ['a', 'b'])
    print('ready', flush=True)
    try:
        ros2lite.spin(node)
    except KeyboardInterrupt:
        pass
"""


@pytest.fixture(scope='module')
def graph(ros_router: str) -> Iterator[str]:
    """The shared node, and test_msgs on the interface path of this process and its CLIs."""
    from ros2lite.interfaces.registry import reload_registry

    saved = os.environ.get('ROS2LITE_INTERFACE_PATH')
    os.environ['ROS2LITE_INTERFACE_PATH'] = DATA
    reload_registry()
    proc = subprocess.Popen(
        [sys.executable, '-c', GRAPH_CODE],
        text=True,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    assert proc.stdout is not None
    line = proc.stdout.readline()
    assert line == 'ready\n', proc.stderr.read() if proc.stderr else line
    try:
        yield NODE
    finally:
        proc.terminate()
        try:
            proc.communicate(timeout=10)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.communicate()
        if saved is None:
            os.environ.pop('ROS2LITE_INTERFACE_PATH', None)
        else:
            os.environ['ROS2LITE_INTERFACE_PATH'] = saved
        reload_registry()


def jq(text: str, program: str = '.') -> list[object]:
    """What `jq -c PROGRAM` makes of `text`: one value per output line (it fails on non-JSON)."""
    proc = subprocess.run(
        ['jq', '-c', program], input=text, capture_output=True, text=True, timeout=10
    )
    assert proc.returncode == 0, proc.stderr + text
    return [json.loads(line) for line in proc.stdout.splitlines()]


def one(result: Result, program: str = '.') -> object:
    """The single JSON document a verb printed (exit 0), through jq."""
    assert result.code == 0, result.err
    assert len(result.out.splitlines()) == 1, result.out
    (value,) = jq(result.out, program)
    return value


Run = Callable[..., Result]


def test_echo_ndjson_round_trips_through_pub(graph: str, run: Run) -> None:
    got = run('topic', 'echo', '--json', '--once', '/json/seq', UNBOUNDED)
    msg = one(got)
    assert isinstance(msg, dict)
    assert msg['byte_values'] == 'AP8=' and msg['char_values'] == 'QUI='
    assert msg['float32_values'] == [1.5, 'nan', '-inf']
    assert msg['float64_values'] == [1e-07, 'inf', -0.0]
    # jq before 1.7 reads numbers as doubles: the text itself holds 64-bit integers exactly
    assert '"int64_values":[-9223372036854775808,9007199254740993]' in got.out
    assert '"uint64_values":[18446744073709551615]' in got.out
    assert msg['basic_types_values'][0]['byte_value'] == 7
    assert msg['basic_types_values'][0]['float64_value'] == 'nan'
    # what echo printed, published again, comes back byte for byte
    line = got.out.strip()
    sub = subprocess.Popen(
        [sys.executable, '-m', 'ros2lite', 'topic', 'echo', '--json', '--once', '/json/back',
         UNBOUNDED, '--timeout', '20'],
        text=True, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
    )  # fmt: skip
    try:
        wait_until(lambda: run('topic', 'info', '/json/back').out.count('Subscription count: 1'))
        pub = run('topic', 'pub', '--once', '-w', '1', '/json/back', UNBOUNDED, line)
        assert pub.code == 0, pub.err
        out, err = sub.communicate(timeout=30)
    finally:
        if sub.poll() is None:
            sub.kill()
    assert out.strip() == line, err


def test_echo_info_wrapper_field_no_arr_and_count(graph: str, run: Run) -> None:
    got = run('topic', 'echo', '--json', '-i', '--once', '/json/seq', UNBOUNDED)
    wrapped = one(got, '{keys: keys, info: .info | keys, n: .message.uint8_values | length}')
    assert wrapped == {
        'keys': ['info', 'message'],
        'info': [
            'publication_sequence_number',
            'received_timestamp',
            'reception_sequence_number',
            'source_timestamp',
        ],
        'n': 344,  # base64 of 256 bytes
    }
    field = run('topic', 'echo', '--json', '--once', '--field', 'uint8_values', '/json/seq')
    assert one(field) == base64.b64encode(bytes(range(256))).decode()
    no_arr = run('topic', 'echo', '--json', '--once', '--no-arr', '/json/seq', UNBOUNDED)
    assert one(no_arr, '.int64_values') == '<sequence type: int64, length: 2>'
    both = run('topic', 'echo', '--json', '--csv', '--once', '/json/seq')
    assert both.code != 0 and both.out == '' and 'pick one' in both.err


def test_service_call_and_action_send_goal(graph: str, run: Run) -> None:
    call = run('service', 'call', '--json', '/json/add', 'example_interfaces/srv/AddTwoInts',
               '{"a": 9007199254740993, "b": 1}')  # fmt: skip
    assert one(call, '[(.request | keys), (.response | keys)]') == [['a', 'b'], ['sum']]
    assert (
        call.out == '{"request":{"a":9007199254740993,"b":1},"response":{"sum":9007199254740994}}\n'
    )
    goal = run('action', 'send_goal', '--json', '-f', '/json/fib',
               'example_interfaces/action/Fibonacci', '{order: 4}')  # fmt: skip
    assert goal.code == 0, goal.err
    lines = jq(goal.out, '.')
    assert lines[0] == {'goal': {'order': 4}, 'accepted': True, 'goal_id': lines[0]['goal_id']}
    assert [x['feedback'] for x in lines[1:-1]] == [
        {'sequence': [0, 1, 1]},
        {'sequence': [0, 1, 1, 2]},
        {'sequence': [0, 1, 1, 2, 3]},
    ]
    assert lines[-1] == {'result': {'sequence': [0, 1, 1, 2, 3]}, 'status': 'SUCCEEDED'}
