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
from tests.conftest import Processes
from tests.spinning import wait_until

pytestmark = pytest.mark.skipif(shutil.which('jq') is None, reason='needs jq')

DATA = str(Path(__file__).parents[1] / 'interfaces' / 'data')  # test_msgs definitions
NODE = '/json/graph'
UNBOUNDED = 'test_msgs/msg/UnboundedSequences'

GRAPH_CODE = """
import math, sys, time
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
        time.sleep(0.05)
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
    from ros2lite.interfaces.registry import default_registry, reload_registry

    before = default_registry()  # put back after: later tests hold its classes
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
        reload_registry(before)


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


def test_service_call_and_action_send_goal_and_echo(
    graph: str, run: Run, processes: Processes
) -> None:
    call = run('service', 'call', '--json', '/json/add', 'example_interfaces/srv/AddTwoInts',
               '{"a": 9007199254740993, "b": 1}')  # fmt: skip
    assert one(call, '[(.request | keys), (.response | keys)]') == [['a', 'b'], ['sum']]
    assert (
        call.out == '{"request":{"a":9007199254740993,"b":1},"response":{"sum":9007199254740994}}\n'
    )
    echo = processes.cli('action', 'echo', '--json', '-i', 'FEEDBACK_TOPIC', '/json/fib')
    feedback = '/json/fib/_action/feedback'
    wait_until(lambda: 'Subscription count: 1' in run('topic', 'info', feedback).out)
    goal = run('action', 'send_goal', '--json', '-f', '/json/fib',
               'example_interfaces/action/Fibonacci', '{order: 4}')  # fmt: skip
    assert goal.code == 0, goal.err
    lines = jq(goal.out, '.')
    assert lines[0] == {'goal': {'order': 4}, 'accepted': True, 'goal_id': lines[0]['goal_id']}
    assert lines[-1] == {'result': {'sequence': [0, 1, 1, 2, 3]}, 'status': 'SUCCEEDED'}
    # feedback travels on a topic and the result on a service: the result may overtake the
    # last feedback, so what arrived is some of them, in order
    got = [x['feedback']['sequence'] for x in lines[1:-1]]
    assert got == sorted(got, key=len) and all(g == [0, 1, 1, 2, 3][: len(g)] for g in got)
    assert all(set(x) == {'feedback'} for x in lines[1:-1])
    assert echo.stdout is not None
    (echoed,) = jq(echo.stdout.readline())
    processes.stop(echo)
    assert isinstance(echoed, dict) and echoed['interface'] == 'FEEDBACK_TOPIC'
    assert echoed['message']['feedback'] == {'sequence': [0, 1, 1]}
    assert set(echoed['message']) == {'goal_id', 'feedback'}


def test_graph_verbs(graph: str, run: Run) -> None:
    wait_until(lambda: graph in str(one(run('node', 'list', '--json'))))
    topics = one(run('topic', 'list', '--json', '-v'), '[.[] | select(.name == "/json/seq")]')
    assert topics == [
        {'name': '/json/seq', 'types': [UNBOUNDED], 'publisher_count': 1, 'subscription_count': 0}
    ]
    assert one(run('topic', 'list', '--json', '-c'), '.count | type') == 'number'
    assert one(run('topic', 'type', '--json', '/json/seq')) == {
        'name': '/json/seq',
        'types': [UNBOUNDED],
    }
    assert one(run('topic', 'find', '--json', UNBOUNDED), '[.[].name]') == ['/json/seq']
    info = one(run('topic', 'info', '--json', '-v', '/json/seq'))
    assert isinstance(info, dict) and info['publisher_count'] == 1 and info['subscriptions'] == []
    (pub,) = info['publishers']
    assert pub['node_name'] == 'graph' and pub['node_namespace'] == '/json'
    assert pub['topic_type_hash'].startswith('RIHS01_') and pub['endpoint_type'] == 'PUBLISHER'
    assert pub['qos']['reliability'] == 'RELIABLE' and pub['qos']['depth'] == 10
    node = one(run('node', 'info', '--json', graph))
    assert isinstance(node, dict) and node['name'] == graph
    assert {'name': '/json/seq', 'types': [UNBOUNDED]} in node['publishers']
    assert {'name': '/json/add', 'types': ['example_interfaces/srv/AddTwoInts']} in node[
        'service_servers'
    ]
    assert node['action_servers'] == [
        {'name': '/json/fib', 'types': ['example_interfaces/action/Fibonacci']}
    ]
    services = one(run('service', 'list', '--json'), '[.[] | select(.name == "/json/add")]')
    assert services == [{'name': '/json/add', 'types': ['example_interfaces/srv/AddTwoInts']}]
    assert one(run('service', 'type', '--json', '/json/add'), '.types') == [
        'example_interfaces/srv/AddTwoInts'
    ]
    assert one(run('action', 'list', '--json')) == [
        {'name': '/json/fib', 'types': ['example_interfaces/action/Fibonacci']}
    ]
    assert one(run('action', 'find', '--json', '-c', 'example_interfaces/action/Fibonacci')) == {
        'count': 1
    }
    # an error stays one line on stderr, with the exit status of the text form
    missing = run('topic', 'type', '--json', '/json/none')
    assert missing.code == 1 and missing.out == '' and 'Unknown topic' in missing.err


def test_param_verbs(graph: str, run: Run) -> None:
    assert one(run('param', 'get', '--json', graph, 'ratio')) == {
        'name': 'ratio',
        'type': 'double',
        'value': 1.5,
    }
    listed = one(run('param', 'list', '--json', '--param-type', graph))
    assert isinstance(listed, dict)
    assert {'name': 'names', 'type': 'string array'} in listed[graph]
    described = one(run('param', 'describe', '--json', graph, 'names'))
    assert isinstance(described, list) and described[0]['name'] == 'names'
    assert described[0]['type'] == 9 and described[0]['read_only'] is False
    dump = one(run('param', 'dump', '--json', graph), f'.["{graph}"].ros__parameters')
    assert isinstance(dump, dict) and dump['ratio'] == 1.5 and dump['names'] == ['a', 'b']


def test_stream_reports_of_hz_and_bw(graph: str, processes: Processes) -> None:
    procs = {
        verb: processes.cli('topic', verb, '--json', '/json/seq', stdin=subprocess.DEVNULL)
        for verb in ('hz', 'bw')
    }
    lines = {}
    for verb, proc in procs.items():
        assert proc.stdout is not None
        lines[verb] = proc.stdout.readline()  # the first report, a second or so in
        processes.stop(proc)
    (hz,) = jq(lines['hz'])
    assert isinstance(hz, dict) and hz['topic'] == '/json/seq' and 5 < hz['rate'] < 40
    assert set(hz) == {'topic', 'rate', 'min', 'max', 'std_dev', 'window'}
    (bw,) = jq(lines['bw'])
    assert isinstance(bw, dict) and bw['count'] > 1 and bw['min'] > 256


def test_interface_verbs(graph: str, run: Run) -> None:
    shown = one(run('interface', 'show', '--json', 'test_msgs/msg/Arrays'))
    assert isinstance(shown, dict) and shown['kind'] == 'message'
    fields = {f['name']: f for f in shown['fields']}
    assert fields['uint8_values'] == {
        'name': 'uint8_values',
        'type': 'uint8',
        'string_bound': None,
        'container': 'array',
        'size': 3,
        'default': None,
    }
    assert fields['float32_values_default']['default'] == [1.125, 0.0, -1.125]
    assert fields['string_values_default']['default'] == ['', 'max value', 'min value']
    assert set(shown['types']) == {
        'test_msgs/msg/BasicTypes',
        'test_msgs/msg/Constants',
        'test_msgs/msg/Defaults',
    }
    constants = one(run('interface', 'show', '--json', 'test_msgs/msg/Constants'), '.constants')
    assert {'name': 'FLOAT64_CONST', 'type': 'float64', 'value': 1.125} in constants
    bounded = one(
        run('interface', 'show', '--json', 'test_msgs/msg/BoundedSequences'),
        '.fields[] | select(.name == "bool_values") | [.container, .size]',
    )
    assert bounded == ['bounded', 3]
    fib = one(run('interface', 'show', '--json', 'example_interfaces/action/Fibonacci'))
    assert isinstance(fib, dict) and fib['kind'] == 'action'
    assert fib['feedback']['fields'][0]['container'] == 'sequence'
    listed = one(run('interface', 'list', '--json', '-s'))
    assert isinstance(listed, dict) and list(listed) == ['services']
    assert 'example_interfaces/srv/AddTwoInts' in listed['services']
    assert 'test_msgs/msg/WStrings' in str(one(run('interface', 'package', '--json', 'test_msgs')))
    assert 'test_msgs' in str(one(run('interface', 'packages', '--json', '-m')))
    # the deprecated msg/srv verbs: interface's documents (their deprecation line on stderr)
    legacy = one(run('msg', 'show', '--json', 'test_msgs/Arrays'))
    assert legacy == one(run('interface', 'show', '--json', 'test_msgs/msg/Arrays'))
    assert one(run('srv', 'show', '--json', 'example_interfaces/srv/AddTwoInts'), '.kind') == (
        'service'
    )
    names = one(run('srv', 'package', '--json', 'example_interfaces'))
    assert isinstance(names, list) and 'example_interfaces/srv/AddTwoInts' in names
    assert 'test_msgs' in str(one(run('msg', 'packages', '--json')))
    assert 'test_msgs/msg/Arrays' in str(one(run('msg', 'list', '--json')))


def test_tool_verbs(run: Run) -> None:
    data = Path(__file__).parents[1] / 'bag' / 'data' / 'mcap' / 'cdr_test'
    bag = one(run('bag', 'info', '--json', str(data)))
    assert isinstance(bag, dict) and bag['storage_identifier'] == 'mcap'
    assert bag['message_count'] == sum(t['message_count'] for t in bag['topics'])
    assert [t['name'] for t in bag['topics']] == ['/array_topic', '/test_topic']
    exes = one(run('pkg', 'executables', '--json', 'turtlesim'), '[.[].name]')
    assert isinstance(exes, list) and 'turtlesim_node' in exes
    assert 'turtlesim' in str(one(run('pkg', 'list', '--json')))
    prefix = one(run('pkg', 'prefix', '--json', 'turtlesim'))
    assert isinstance(prefix, dict) and Path(prefix['share']).name == 'turtlesim'
    assert one(run('bag', 'list', '--json', 'storage'), '[.[].name]') == [
        'mcap',
        'sqlite3',
        'rosbag1',
    ]
    manifest = one(run('pkg', 'xml', '--json', 'turtlesim'))
    assert isinstance(manifest, dict) and manifest['tag'] == 'package'
    assert {'tag': 'name', 'attributes': {}, 'text': 'turtlesim', 'children': []} in manifest[
        'children'
    ]
    assert one(run('pkg', 'xml', '--json', 'turtlesim', '-t', 'name')) == ['turtlesim']
    proto = run('interface', 'proto', '--json', 'example_interfaces/srv/AddTwoInts')
    assert one(proto) == {'a': 0, 'b': 0}
    status = one(run('daemon', 'status', '--json'), '[.running, (.endpoint | type)]')
    assert status[1] == 'string'
    doctor = one(run('doctor', '--json'), '[.checks[].category, (.failed | type)]')
    assert isinstance(doctor, list) and 'platform' in doctor and doctor[-1] == 'array'


def test_lifecycle_and_component_verbs(graph: str, run: Run, processes: Processes) -> None:
    processes.cli('run', 'lifecycle_py', 'lifecycle_talker', '--ros-args', '-r', '__ns:=/json')
    wait_until(lambda: run('lifecycle', 'nodes', '--json').out.count('/json/lc_talker'))
    assert one(run('lifecycle', 'nodes', '--json')) == ['/json/lc_talker']
    assert one(run('lifecycle', 'get', '--json', '/json/lc_talker')) == {
        '/json/lc_talker': {'label': 'unconfigured', 'id': 1}
    }
    moves = one(run('lifecycle', 'list', '--json', '/json/lc_talker'))
    assert isinstance(moves, list)
    assert {'label': 'configure', 'id': 1, 'start': 'unconfigured', 'goal': 'configuring'} in moves
    types = one(run('component', 'types', '--json'))
    assert isinstance(types, dict) and 'composition::Talker' in types['composition']
