"""`foxglove_bridge` seen by a client no one here wrote: the protocol's own npm client
(`@foxglove/ws-protocol` over `ws`, decoding with `@foxglove/rosmsg2-serialization`), driven
through tests/js/foxglove_client.js, against turtlesim and publishers of images and tf."""

from __future__ import annotations

import base64
import json
import math
import queue
import re
import shutil
import subprocess
import threading
import time
from collections import Counter
from pathlib import Path
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import definition_text, get_interface
from tests.spinning import free_port, spin_for, wait_until

JS = Path(__file__).resolve().parents[1] / 'js'
pytestmark = pytest.mark.skipif(
    shutil.which('node') is None or not (JS / 'node_modules' / '@foxglove').is_dir(),
    reason='needs node and `npm ci --prefix tests/js`',
)

# /chatter, a 64x48 rgb8 image and a tf message, with values the client must decode
PUBLISHERS = r'''
import ros2lite
from ros2lite.node import Node
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.msgs.sensor_msgs.msg import Image
from ros2lite.msgs.tf2_msgs.msg import TFMessage
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
ros2lite.init()
node = Node('fox_publishers')
chatter = node.create_publisher(String, 'chatter', 10)
camera = node.create_publisher(Image, 'camera/image', 10)
tf = node.create_publisher(TFMessage, '/tf', 10)
count = [0]
image = Image(height=48, width=64, encoding='rgb8', step=64 * 3,
              data=bytes(i % 251 for i in range(64 * 48 * 3)))
image.header.frame_id = 'camera'
t = TransformStamped()
t.header.frame_id = 'map'
t.child_frame_id = 'base_link'
t.transform.translation.x = 1.5
t.transform.rotation.w = 1.0
def tick():
    count[0] += 1
    chatter.publish(String(data=f'fox {count[0]}'))
    camera.publish(image)
    tf.publish(TFMessage(transforms=[t]))
node.create_timer(0.05, tick)
ros2lite.spin(node)
'''


class JsClient:
    """The npm client as a process: commands in, events out (JSON lines)."""

    def __init__(self, port: int, protocols: str = 'foxglove.sdk.v1') -> None:
        self.proc = subprocess.Popen(
            ['node', str(JS / 'foxglove_client.js'), f'ws://127.0.0.1:{port}', protocols],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            text=True,
            cwd=JS,
        )
        self.events: queue.Queue[dict[str, Any]] = queue.Queue()
        self.seen: list[dict[str, Any]] = []
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self) -> None:
        assert self.proc.stdout is not None
        for line in self.proc.stdout:
            try:
                self.events.put(json.loads(line))
            except ValueError:  # a line cut short when the client is killed at teardown
                self.events.put({'event': 'garbled', 'line': line})

    def send(self, **cmd: Any) -> None:
        assert self.proc.stdin is not None
        try:
            self.proc.stdin.write(json.dumps(cmd) + '\n')
            self.proc.stdin.flush()
        except BrokenPipeError:  # the server dropped it, and it ended: events tell
            pass

    def expect(self, pred: Any, timeout: float = 20.0) -> dict[str, Any]:
        """The first event (seen before or arriving) for which `pred` holds."""
        for ev in self.seen:
            if pred(ev):
                self.seen.remove(ev)
                return ev
        deadline = time.monotonic() + timeout
        while True:
            left = deadline - time.monotonic()
            assert left > 0, f'no matching event; saw {Counter(e["event"] for e in self.seen)}'
            try:
                ev = self.events.get(timeout=left)
            except queue.Empty:
                continue
            if pred(ev):
                return ev
            self.seen.append(ev)

    def channels(self, topics: set[str], timeout: float = 20.0) -> dict[str, dict[str, Any]]:
        found: dict[str, dict[str, Any]] = {}
        while not topics <= set(found):
            ev = self.expect(lambda e: e['event'] == 'advertise', timeout)
            found.update({c['topic']: c for c in ev['channels']})
        return found

    def message(self, topic: str, timeout: float = 20.0) -> Any:
        ev = self.expect(lambda e: e['event'] == 'message' and e['topic'] == topic, timeout)
        return ev['value']

    def close(self) -> None:
        if self.proc.poll() is None:
            self.proc.kill()
        self.proc.wait()


def start_bridge(processes: Any, *params: str) -> tuple[Any, int, list[str]]:
    """The bridge on a free port, once it listens; its stderr lines keep arriving in the
    list (read on a thread, so a chatty bridge never blocks on a full pipe)."""
    port = free_port()
    args = ['-p', f'port:={port}']
    for p in params:
        args += ['-p', p]
    proc = processes.cli('run', 'foxglove_bridge', 'foxglove_bridge', '--ros-args', *args)
    lines: list[str] = []
    listening = threading.Event()

    def read() -> None:
        for line in proc.stderr:
            lines.append(line)
            if 'Foxglove bridge listening on ws://127.0.0.1:' in line:
                listening.set()

    threading.Thread(target=read, daemon=True).start()
    deadline = time.monotonic() + 30
    while not listening.wait(0.1):
        assert proc.poll() is None and time.monotonic() < deadline, ''.join(lines)
    return proc, port, lines


@pytest.fixture
def client_factory() -> Any:
    made: list[JsClient] = []

    def make(port: int, protocols: str = 'foxglove.sdk.v1') -> JsClient:
        c = JsClient(port, protocols)
        made.append(c)
        return c

    yield make
    for c in made:
        c.close()


def test_npm_client_sees_decodes_publishes_calls_and_sets(
    processes: Any, client_factory: Any, ros_context: Any
) -> None:
    processes.cli('run', 'turtlesim', 'turtlesim_node', '--display', 'none')
    processes.python(PUBLISHERS)
    bridge, port, _ = start_bridge(processes)
    client = client_factory(port)
    opened = client.expect(lambda e: e['event'] == 'open')
    assert opened['protocol'] == 'foxglove.sdk.v1'
    info = client.expect(lambda e: e['event'] == 'serverInfo')['info']
    assert {'clientPublish', 'parameters', 'services', 'connectionGraph'} <= set(
        info['capabilities']
    )

    # every topic a channel, with a schema the ecosystem's parser takes
    wanted = {'/chatter', '/turtle1/pose', '/camera/image', '/tf', '/turtle1/cmd_vel'}
    channels = client.channels(wanted)
    for topic in wanted:
        assert channels[topic]['parsed'], channels[topic]
    assert channels['/camera/image']['schemaName'] == 'sensor_msgs/msg/Image'
    assert channels['/tf']['schemaName'] == 'tf2_msgs/msg/TFMessage'

    # subscribing decodes what the publishers sent
    for topic in ('/chatter', '/turtle1/pose', '/camera/image', '/tf'):
        client.send(cmd='subscribe', topic=topic, decode=1)
    assert re.fullmatch(r'fox \d+', client.message('/chatter')['data'])
    pose = client.message('/turtle1/pose')
    assert math.isclose(pose['x'], 5.544444561004639, rel_tol=1e-6), pose
    image = client.message('/camera/image')
    assert (image['width'], image['height'], image['encoding'], image['step']) == (
        64,
        48,
        'rgb8',
        192,
    )
    pixels = bytes(i % 251 for i in range(64 * 48 * 3))
    assert image['data']['length'] == len(pixels)
    assert image['data']['sum'] == sum(pixels) % 1000000007
    assert image['header']['frame_id'] == 'camera'
    tf = client.message('/tf')['transforms'][0]
    assert (tf['header']['frame_id'], tf['child_frame_id']) == ('map', 'base_link')
    assert tf['transform']['translation']['x'] == 1.5

    # a Twist from the client moves the turtle
    twist = {'linear': {'x': 2.0, 'y': 0.0, 'z': 0.0}, 'angular': {'x': 0.0, 'y': 0.0, 'z': 0.0}}
    schema = definition_text('geometry_msgs/msg/Twist')
    client.send(cmd='unsubscribe', topic='/turtle1/pose')
    for _ in range(5):
        client.send(
            cmd='publish',
            topic='/turtle1/cmd_vel',
            schemaName='geometry_msgs/msg/Twist',
            schema=schema,
            value=twist,
        )
        time.sleep(0.1)  # turtlesim's command timeout is 1 s: keep it moving a little
    client.send(cmd='subscribe', topic='/turtle1/pose', decode=200)
    deadline = time.monotonic() + 20
    while client.message('/turtle1/pose')['x'] < 5.8:
        assert time.monotonic() < deadline

    # a client that sends JSON (the bridge advertises both encodings)
    from ros2lite.node import Node

    got: list[str] = []
    listener = Node('fox_listener', context=ros_context)
    listener.create_subscription(
        get_interface('std_msgs/msg/String'), '/from_json', lambda m: got.append(m.data), 10
    )
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(listener)
    deadline = time.monotonic() + 20
    while not got:  # the first may go out before the new publisher has met the listener
        assert time.monotonic() < deadline
        client.send(
            cmd='publish',
            topic='/from_json',
            schemaName='std_msgs/msg/String',
            encoding='json',
            value={'data': 'json hello'},
        )
        spin_for(executor, 0.3)
    assert set(got) == {'json hello'}

    # /spawn through the bridge
    client.expect(
        lambda e: (
            e['event'] == 'advertiseServices' and any(s['name'] == '/spawn' for s in e['services'])
        )
    )
    client.send(
        cmd='call', service='/spawn', request={'x': 2.0, 'y': 2.0, 'theta': 0.0, 'name': 'fox'}
    )
    assert client.expect(lambda e: e['event'] == 'serviceResponse')['value'] == {'name': 'fox'}
    assert '/fox/pose' in client.channels({'/fox/pose'})

    # a turtlesim parameter, read and set under the C++ bridge's /node.param name
    client.send(cmd='getParameters', names=['/turtlesim.background_r'], id='get')
    got = client.expect(lambda e: e['event'] == 'parameterValues' and e.get('id') == 'get')
    assert got['parameters'] == [{'name': '/turtlesim.background_r', 'value': 69}]
    client.send(
        cmd='setParameters', parameters=[{'name': '/turtlesim.background_r', 'value': 10}], id='set'
    )
    done = client.expect(lambda e: e['event'] == 'parameterValues' and e.get('id') == 'set')
    assert done['parameters'] == [{'name': '/turtlesim.background_r', 'value': 10}]
    # all of them (what the Foxglove app asks first), and one watched for changes
    client.send(cmd='getParameters', names=[], id='all')
    every = client.expect(lambda e: e['event'] == 'parameterValues' and e.get('id') == 'all')
    names = {p['name'] for p in every['parameters']}
    assert {'/turtlesim.background_g', '/foxglove_bridge.port'} <= names
    client.send(cmd='subscribeParameters', names=['/turtlesim.background_g'])
    client.send(
        cmd='setParameters', parameters=[{'name': '/turtlesim.background_g', 'value': 7}], id='g'
    )
    changed = client.expect(lambda e: e['event'] == 'parameterValues' and e.get('id') is None)
    assert changed['parameters'] == [{'name': '/turtlesim.background_g', 'value': 7}]

    # the connection graph
    client.send(cmd='subscribeGraph')
    published: dict[str, list[str]] = {}
    services: dict[str, list[str]] = {}
    while '/turtle1/pose' not in published or '/spawn' not in services:
        graph = client.expect(lambda e: e['event'] == 'connectionGraph')['graph']
        published.update({t['name']: t['publisherIds'] for t in graph['publishedTopics']})
        services.update({s['name']: s['providerIds'] for s in graph['advertisedServices']})
    assert published['/turtle1/pose'] == ['/turtlesim']
    assert '/fox_publishers' in published['/camera/image']
    assert services['/spawn'] == ['/turtlesim']
    assert bridge.poll() is None


def test_bad_clients_get_errors_not_a_crash(processes: Any, client_factory: Any) -> None:
    processes.python(PUBLISHERS)
    bridge, port, log = start_bridge(processes)
    bad = client_factory(port)
    bad.expect(lambda e: e['event'] == 'open')
    bad.channels({'/chatter'})

    def error_status(text: str) -> str:
        ev = bad.expect(lambda e: e['event'] == 'status' and text in e['message'])
        assert ev['level'] == 2  # error
        return str(ev['message'])

    bad.send(cmd='raw', data='{"op": "nonsense"')
    error_status('Invalid message')
    bad.send(cmd='raw', data='AAECAwQFBgc=', binary=True)
    error_status('Unknown binary opcode')
    bad.send(
        cmd='publish', topic='/nowhere', schemaName='no_such/msg/Type', encoding='cdr', bytes=[0]
    )
    assert "Cannot advertise '/nowhere'" in bad.expect(lambda e: e['event'] == 'status')['message']
    # 10,000 unknown channel ids: an error each, until the client's control queue is full
    # (the SDK's message_backlog_size) and it is dropped (with what was still queued for it)
    bad.send(cmd='subscribeIds', first=5000, count=10000)
    first = bad.expect(
        lambda e: (
            e['event'] == 'close' or (e['event'] == 'status' and 'Unknown channel' in e['message'])
        )
    )
    if first['event'] == 'status':
        assert first == {'event': 'status', 'level': 2, 'message': 'Unknown channel ID: 5000'}
        last = bad.expect(
            lambda e: (
                e['event'] == 'close'
                or (e['event'] == 'status' and e['message'] == 'Unknown channel ID: 14999')
            )
        )
        assert last['event'] == 'close' or last['level'] == 2
    # data on a channel it never advertised, 32 MiB of it: over the SDK's frame limit
    huge = bytearray(32 * 1024 * 1024)
    huge[0] = 0x01  # client message data opcode
    huge[1:5] = (77).to_bytes(4, 'little')
    big = client_factory(port)
    big.expect(lambda e: e['event'] == 'open')
    big.send(cmd='raw', data=base64.b64encode(bytes(huge)).decode(), binary=True)
    assert big.expect(lambda e: e['event'] == 'close')['code'] == 1006  # dropped
    # the bridge lives, and a well-behaved client is served meanwhile
    good = client_factory(port, 'foxglove.sdk.v1,foxglove.websocket.v1')
    assert good.expect(lambda e: e['event'] == 'open')['protocol'] == 'foxglove.sdk.v1'
    good.channels({'/chatter'})
    good.send(cmd='subscribe', topic='/chatter', decode=3)
    for _ in range(3):
        assert good.message('/chatter')['data'].startswith('fox ')
    assert bridge.poll() is None, processes.stop(bridge)
    # the SDK's one warning per unknown id is throttled, not 10,000 lines
    unknown = [line for line in log if 'unknown channel' in line]
    assert 1 <= len(unknown) <= 50, len(unknown)


BIG_IMAGES = r'''
import ros2lite
from ros2lite.node import Node
from ros2lite.interfaces import serialize
from ros2lite.msgs.sensor_msgs.msg import Image
ros2lite.init()
node = Node('big_images')
pub = node.create_publisher(Image, 'big', 10)
data = serialize(Image(height=512, width=512, encoding='rgba8', step=2048, data=bytes(1 << 20)))
node.create_timer(1 / 30, lambda: pub.publish(data))
ros2lite.spin(node)
'''


def test_a_client_that_stops_reading_is_told_its_messages_drop(
    processes: Any, client_factory: Any
) -> None:
    processes.python(BIG_IMAGES)
    bridge, port, _ = start_bridge(processes, 'message_backlog_size:=8')
    client = client_factory(port)
    client.channels({'/big'})
    client.send(cmd='subscribe', topic='/big', decode=0)
    client.send(cmd='counts')
    deadline = time.monotonic() + 20
    while client.expect(lambda e: e['event'] == 'counts')['counts']['/big']['received'] < 3:
        assert time.monotonic() < deadline
        time.sleep(0.1)
        client.send(cmd='counts')
    client.send(cmd='pause')  # the socket stops being read: the kernel's buffers fill, then ours
    time.sleep(3)
    client.send(cmd='resume')
    status = client.expect(lambda e: e['event'] == 'status')
    assert status['level'] == 1  # warning
    assert 'Send buffer limit reached for client 127.0.0.1:' in status['message']
    assert bridge.poll() is None


def test_channels_follow_the_graph_and_zenoh_subscriptions_follow_clients(
    processes: Any, client_factory: Any, ros_context: Any
) -> None:
    from ros2lite.node import Node

    publishers = processes.python(PUBLISHERS)
    _, port, _ = start_bridge(processes)
    watcher = Node('fox_watcher', context=ros_context)

    def bridge_subscribes(topic: str) -> bool:
        infos = watcher.get_subscriptions_info_by_topic(topic)
        return any(i.node_name == 'foxglove_bridge' for i in infos)

    client = client_factory(port)
    client.channels({'/chatter', '/camera/image'})
    time.sleep(0.5)  # (nothing should happen: give it the chance to)
    assert not bridge_subscribes('/camera/image')
    client.send(cmd='subscribe', topic='/camera/image', decode=1)
    wait_until(lambda: bridge_subscribes('/camera/image'), timeout=20)
    assert client.message('/camera/image')['width'] == 64
    client.send(cmd='unsubscribe', topic='/camera/image')
    wait_until(lambda: not bridge_subscribes('/camera/image'), timeout=20)

    # a client that offers neither name of the protocol is refused
    stranger = client_factory(port, 'foxglove.websocket.v2')
    assert stranger.expect(lambda e: e['event'] in ('rejected', 'open')) == {
        'event': 'rejected',
        'status': 400,
    }

    # the publishers leave: their channels go
    processes.stop(publishers)
    gone: set[str] = set()
    while not {'/chatter', '/camera/image', '/tf'} <= gone:
        gone.update(client.expect(lambda e: e['event'] == 'unadvertise')['topics'])


def test_launch_file_takes_the_cpp_packages_arguments(processes: Any, client_factory: Any) -> None:
    port = free_port()
    launch = processes.cli(
        'launch',
        'foxglove_bridge',
        'foxglove_bridge_launch.xml',
        f'port:={port}',
        "topic_whitelist:=['/chatter']",
        'capabilities:=[services]',
        'use_sim_time:=true',
    )
    processes.python(PUBLISHERS)
    processes.cli(
        'topic',
        'pub',
        '-r',
        '20',
        '/clock',
        'rosgraph_msgs/msg/Clock',
        '{clock: {sec: 1234, nanosec: 5}}',
    )
    client = client_factory(port)
    deadline = time.monotonic() + 30
    while client.expect(lambda e: e['event'] in ('open', 'error'))['event'] != 'open':
        assert time.monotonic() < deadline and launch.poll() is None  # not listening yet
        client.close()
        time.sleep(0.2)
        client = client_factory(port)
    info = client.expect(lambda e: e['event'] == 'serverInfo')['info']
    assert sorted(info['capabilities']) == ['services', 'time']  # time: use_sim_time
    assert client.expect(lambda e: e['event'] == 'time')['timestamp'] == 1234_000_000_005
    client.channels({'/chatter'})
    client.send(cmd='subscribe', topic='/chatter', decode=1)
    client.message('/chatter')  # the publishers are up: their channels (if any) exist now
    late = client_factory(port)
    shown = late.expect(lambda e: e['event'] == 'advertise')['channels']
    assert [c['topic'] for c in shown] == ['/chatter']  # the whitelist holds (not /clock)


def test_a_type_only_a_node_knows_gets_its_schema_from_that_node(
    processes: Any, client_factory: Any, tmp_path: Path
) -> None:
    """The bridge has no definition of the topic's type: it asks the publishing node for it
    and advertises the channel with the full schema, which the npm client decodes with."""
    import os

    from tests.test_remote_types import NODE, write_workspace

    workspace = write_workspace(tmp_path)
    env = {**os.environ, 'ROS2LITE_INTERFACE_PATH': str(workspace)}
    node = processes.python(NODE, 'honest', env=env)
    assert node.stdout.readline().strip() == 'READY'
    _, port, lines = start_bridge(processes)
    client = client_factory(port)
    channel = client.channels({'/lab/reading'})['/lab/reading']
    assert channel['schemaName'] == 'wire_test_msgs/msg/Reading' and channel['parsed']
    # decoding needs the whole schema: the nested Sample's section too
    client.send(cmd='subscribe', topic='/lab/reading', decode=1)
    reading = client.message('/lab/reading')
    assert reading['level'] == 2 and reading['samples'][0]['value'] == 1.5
    assert any(
        'type wire_test_msgs/msg/Reading fetched from node /lab/sensor' in line for line in lines
    )
    # the node's service of a type only it knows is offered too, and answers
    client.expect(
        lambda e: (
            e['event'] == 'advertiseServices'
            and any(s['name'] == '/lab/scale' for s in e['services'])
        )
    )
    client.send(cmd='call', service='/lab/scale', request={'x': 2.0, 's': {'value': 4.0}})
    assert client.expect(lambda e: e['event'] == 'serviceResponse')['value']['y'] == 8.0
