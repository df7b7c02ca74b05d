"""Any type straight from the wire: a node publishes a type defined only in a workspace the
CLI cannot see; from another directory the CLI echoes it, publishes it, calls its service,
records it (the bag read back by `bag info` and by `rosbags`) and shows it, each time fetched
from the node's `~/get_type_description`. A node whose description does not fit the hash it
announces gets one line and a non-zero exit."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from tests.spinning import wait_until

READING = """\
# A reading no package on the CLI's side defines
uint8 LEVEL_LOW=1
uint8 LEVEL_HIGH=2
std_msgs/Header header
Sample[] samples
uint8 level
string note "none"
"""
SAMPLE = 'float64 value\nint32[3] counts\n'
SCALE = 'float64 x\nSample s\n---\nfloat64 y\n'
COUNT = 'int32 to\n---\nint32 reached\n---\nSample last\n'

NODE = """
import sys
import ros2lite as rclpy
from ros2lite.interfaces import get_interface
rclpy.init()
node = rclpy.create_node('sensor', namespace='/lab')
Reading = get_interface('wire_test_msgs/msg/Reading')
Sample = get_interface('wire_test_msgs/msg/Sample')
Scale = get_interface('wire_test_msgs/srv/Scale')
if sys.argv[1] == 'lie':  # serve a description with one field more than the hash counts
    import ros2lite.type_description_service as tds
    FieldMsg = get_interface('type_description_interfaces/msg/Field')
    FieldType = get_interface('type_description_interfaces/msg/FieldType')
    true_description = tds.description_message
    def lying(name):
        d = true_description(name)
        d.type_description.fields.append(FieldMsg(name='extra', type=FieldType(type_id=6)))
        return d
    tds.description_message = lying
pub = node.create_publisher(Reading, 'reading', 10)
def scale(req, resp):
    resp.y = req.x * req.s.value
    return resp
node.create_service(Scale, 'scale', scale)
from ros2lite.action import ActionServer
Count = get_interface('wire_test_msgs/action/Count')
def count_to(goal):
    goal.succeed()
    return Count.Result(reached=goal.request.to)
ActionServer(node, Count, 'count', count_to)
def heard(m):
    print('GOT', m.level, m.note, flush=True)
node.create_subscription(Reading, 'command', heard, 10)
count = 0
def tick():
    global count
    count += 1
    pub.publish(Reading(samples=[Sample(value=1.5, counts=[1, 2, count])],
                        level=Reading.LEVEL_HIGH, note=f'n{count}'))
node.create_timer(0.1, tick)
print('READY', flush=True)
rclpy.spin(node)
"""


def write_workspace(root: Path) -> Path:
    """`root/ws`: a package of interfaces only the node's environment names."""
    pkg = root / 'ws' / 'wire_test_msgs'
    (pkg / 'msg').mkdir(parents=True)
    (pkg / 'srv').mkdir()
    (pkg / 'action').mkdir()
    (pkg / 'action' / 'Count.action').write_text(COUNT)
    (pkg / 'msg' / 'Reading.msg').write_text(READING)
    (pkg / 'msg' / 'Sample.msg').write_text(SAMPLE)
    (pkg / 'srv' / 'Scale.srv').write_text(SCALE)
    return root / 'ws'


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    """The workspace, and a directory `elsewhere` for the CLI to run in."""
    write_workspace(tmp_path)
    (tmp_path / 'elsewhere').mkdir()
    return tmp_path


def _node(processes: Any, workspace: Path, mode: str = 'honest') -> Any:
    env = {**os.environ, 'ROS2LITE_INTERFACE_PATH': str(workspace / 'ws')}
    proc = processes.python(NODE, mode, env=env, cwd=str(workspace / 'elsewhere'))
    assert proc.stdout.readline().strip() == 'READY'
    return proc


def _cli(workspace: Path, *args: str, timeout: float = 30) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k != 'ROS2LITE_INTERFACE_PATH'}
    return subprocess.run(
        [sys.executable, '-m', 'ros2lite', *args],
        capture_output=True,
        text=True,
        env=env,
        cwd=str(workspace / 'elsewhere'),
        timeout=timeout,
    )


FETCHED = 'ros2lite: type wire_test_msgs/msg/Reading fetched from node /lab/sensor\n'


def test_echo_show_pub_and_call_a_type_only_the_node_knows(processes: Any, workspace: Path) -> None:
    node = _node(processes, workspace)
    echo = _cli(workspace, 'topic', 'echo', '--once', '/lab/reading')
    assert echo.returncode == 0, echo.stderr
    assert echo.stderr == FETCHED
    assert 'samples:\n- value: 1.5\n  counts:\n  - 1\n  - 2\n' in echo.stdout
    assert 'level: 2\nnote: n' in echo.stdout

    show = _cli(workspace, 'interface', 'show', 'wire_test_msgs/msg/Reading')
    assert show.returncode == 0, show.stderr
    assert show.stdout.startswith(READING.split('std_msgs')[0] + 'std_msgs/Header header\n')
    assert '\tfloat64 value\n\tint32[3] counts\n' in show.stdout

    action = _cli(workspace, 'interface', 'show', 'wire_test_msgs/action/Count')
    assert action.returncode == 0, action.stderr
    assert action.stderr == FETCHED.replace('msg/Reading', 'action/Count')
    assert action.stdout == (
        'int32 to\n---\nint32 reached\n---\nwire_test_msgs/Sample last\n'
        '\tfloat64 value\n\tint32[3] counts\n'
    )

    call = _cli(
        workspace, 'service', 'call', '/lab/scale', 'wire_test_msgs/srv/Scale',
        '{x: 2.0, s: {value: 4.0}}', '--timeout', '10',
    )  # fmt: skip
    assert call.returncode == 0, call.stderr
    assert 'fetched from node /lab/sensor' in call.stderr
    assert 'y=8.0' in call.stdout

    goal = _cli(
        workspace, 'action', 'send_goal', '/lab/count', 'wire_test_msgs/action/Count', '{to: 3}',
        '--json', '--timeout', '10',
    )  # fmt: skip
    assert goal.returncode == 0, goal.stderr
    assert goal.stderr.startswith(FETCHED.replace('msg/Reading', 'action/Count'))
    lines = [json.loads(line) for line in goal.stdout.splitlines()]
    assert lines[0]['goal'] == {'to': 3} and lines[0]['accepted'] is True
    assert lines[-1] == {'result': {'reached': 3}, 'status': 'SUCCEEDED'}

    pub = _cli(
        workspace, 'topic', 'pub', '-1', '-w', '1', '/lab/command', 'wire_test_msgs/msg/Reading',
        '{level: 1, note: hello}',
    )  # fmt: skip
    assert pub.returncode == 0, pub.stderr
    assert wait_until(lambda: 'GOT 1 hello' in node.stdout.readline(), timeout=10)


def test_record_a_type_only_the_node_knows(
    processes: Any, workspace: Path, ros_context: Any
) -> None:
    from ros2lite.bag.definitions import type_ref
    from ros2lite.interfaces.hashing import type_hash
    from ros2lite.interfaces.registry import BUNDLED, Registry
    from tests.spinning import Listener

    _node(processes, workspace)
    # the test's own witness of what was published (raw bytes, under the node's hash)
    name = 'wire_test_msgs/msg/Reading'
    wire = type_hash(name, Registry(roots=[workspace / 'ws', BUNDLED]))
    witness = Listener(ros_context, '/lab/reading', type_ref(name, wire), 10, raw=True)
    bag = workspace / 'elsewhere' / 'bag'
    rec = processes.cli(
        'bag', 'record', '-o', str(bag), '/lab/reading',
        cwd=str(workspace / 'elsewhere'),
        env={k: v for k, v in os.environ.items() if k != 'ROS2LITE_INTERFACE_PATH'},
    )  # fmt: skip
    err = ''
    while "Subscribed to topic '/lab/reading'" not in err:
        line = rec.stderr.readline()
        assert line, err
        err += line
    seen = len(witness.messages)
    assert wait_until(lambda: len(witness.messages) >= seen + 3, timeout=10)
    witness.stop()
    _, rest = processes.stop(rec)
    assert FETCHED in err + rest
    info = _cli(workspace, 'bag', 'info', str(bag))
    assert info.returncode == 0, info.stderr
    assert 'wire_test_msgs/msg/Reading' in info.stdout
    assert 'Count: 0' not in info.stdout

    from rosbags.highlevel import AnyReader

    with AnyReader([bag]) as reader:
        connection = next(c for c in reader.connections if c.topic == '/lab/reading')
        raw = next(reader.messages(connections=[connection]))[2]
        msg = reader.deserialize(raw, connection.msgtype)
    assert msg.level == 2 and msg.samples[0].value == 1.5
    assert list(msg.samples[0].counts[:2]) == [1, 2]


def test_a_node_lying_about_its_type_gets_one_line(processes: Any, workspace: Path) -> None:
    _node(processes, workspace, 'lie')
    echo = _cli(workspace, 'topic', 'echo', '--once', '/lab/reading')
    assert echo.returncode == 1
    assert echo.stdout == ''
    lines = echo.stderr.splitlines()
    assert len(lines) == 1, echo.stderr
    assert 'node /lab/sensor describes wire_test_msgs/msg/Reading as RIHS01_' in lines[0]
    assert 'not as the RIHS01_' in lines[0]


def test_only_nodes_that_describe_are_asked_publishers_on_the_topic_first() -> None:
    from ros2lite.graph import Entity, EntityKind
    from ros2lite.remote_types import SERVICE_TYPE, offering_nodes

    def endpoint(kind: EntityKind, node: str, topic: str, type_name: str) -> Entity:
        return Entity(0, 'z', 1, 2, kind, '/', '/', node, topic, type_name, None, 'RIHS01_x')

    entities = [
        endpoint(EntityKind.SUBSCRIPTION, 'b', '/t', 'p/msg/T'),
        endpoint(EntityKind.PUBLISHER, 'a', '/other', 'p/msg/T'),
        endpoint(EntityKind.PUBLISHER, 'c', '/t', 'p/msg/T'),
        endpoint(EntityKind.PUBLISHER, '_ros2lite_tool', '/t', 'p/msg/T'),  # serves nothing
        *(
            endpoint(EntityKind.SERVICE, n, f'/{n}/get_type_description', SERVICE_TYPE)
            for n in 'abc'
        ),
    ]
    assert [n for n, _, _ in offering_nodes(entities, 'p/msg/T', '/t')] == ['/c', '/b', '/a']
    assert offering_nodes(entities, 'p/msg/U', '/t') == []
