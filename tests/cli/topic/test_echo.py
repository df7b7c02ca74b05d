"""`topic echo` against live publishers: formats, options, type discovery, QoS and errors."""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

from ros2lite.interfaces import get_interface, serialize
from ros2lite.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

from ...conftest import wait_until
from ..conftest import Result
from .conftest import has_endpoint

String = get_interface('std_msgs/msg/String')
Int32 = get_interface('std_msgs/msg/Int32')
HELLO = re.compile(r"data: 'Hello World: (\d+)'\n---\n")
# safety net: a broken echo fails the test instead of hanging it
LIMIT = ('--timeout', '10')


def hello(i: int) -> Any:
    return String(data=f'Hello World: {i}')


def test_once_prints_one_yaml_message(run: Callable[..., Result], talker: Any, topic: str) -> None:
    talker(topic, 'std_msgs/msg/String', hello)
    result = run('topic', 'echo', topic, '--once', *LIMIT)
    assert result.code == 0, result.err
    assert HELLO.fullmatch(result.out), result.out
    assert result.err == ''


def test_explicit_type_and_short_type_name(
    run: Callable[..., Result], talker: Any, topic: str
) -> None:
    talker(topic, 'std_msgs/msg/String', hello)
    for type_name in ('std_msgs/msg/String', 'std_msgs/String'):
        result = run('topic', 'echo', topic, type_name, '--once', *LIMIT)
        assert result.code == 0 and HELLO.fullmatch(result.out), result


def test_stream_of_messages_until_timeout(
    run: Callable[..., Result], talker: Any, topic: str
) -> None:
    talker(topic, 'std_msgs/msg/String', hello, rate=20)
    result = run('topic', 'echo', topic, '--timeout', '0.6')
    assert result.code == 0
    numbers = [int(n) for n in HELLO.findall(result.out)]
    assert len(numbers) >= 3
    assert HELLO.sub('', result.out) == ''  # nothing but messages
    assert numbers == list(range(numbers[0], numbers[0] + len(numbers)))


def test_timeout_without_publisher_exits_zero_silently(
    run: Callable[..., Result], topic: str
) -> None:
    result = run('topic', 'echo', topic, 'std_msgs/msg/String', '--timeout', '0.3')
    assert (result.code, result.out, result.err) == (0, '', '')


def test_unknown_topic_cannot_determine_type(run: Callable[..., Result], topic: str) -> None:
    result = run('topic', 'echo', topic, '--timeout', '0.3')
    assert result.code == 1
    assert result.out == f'WARNING: topic [{topic}] does not appear to be published yet\n'
    assert result.err == 'Could not determine the type for the passed topic\n'


def test_invalid_message_types(run: Callable[..., Result], topic: str) -> None:
    for bad in ('std_msgs/msg/Nope', 'nope_msgs/msg/X', 'garbage', 'std_srvs/srv/Empty'):
        result = run('topic', 'echo', topic, bad, '--once')
        assert (result.code, result.err) == (1, 'The passed message type is invalid\n'), bad


def test_invalid_topic_name(run: Callable[..., Result]) -> None:
    result = run('topic', 'echo', '/a//b', 'std_msgs/msg/String', '--once')
    assert result.code == 1 and "'/a//b'" in result.err and result.err.count('\n') == 1


def test_topic_with_two_types_is_refused(
    run: Callable[..., Result], talker: Any, topic: str
) -> None:
    talker(topic, 'std_msgs/msg/String', hello)
    talker(topic, 'std_msgs/msg/Int32', lambda i: Int32(data=i), node_name='other')
    result = run('topic', 'echo', topic, '--once')
    assert result.code == 1
    assert result.err == (
        f"Cannot echo topic '{topic}', as it contains more than one type: "
        '[std_msgs/msg/Int32, std_msgs/msg/String]\n'
    )


def test_type_not_published_is_said_at_once(
    run: Callable[..., Result], talker: Any, ros_context: Any, topic: str
) -> None:
    talker(topic, 'std_msgs/msg/String', hello)
    wait_until(lambda: has_endpoint(ros_context, topic, 'MP'))
    result = run('topic', 'echo', topic, 'std_msgs/msg/Int32', '--timeout', '0.5')
    assert (result.code, result.out) == (0, '')
    assert result.err == (
        f"WARNING: topic '{topic}' is published as std_msgs/msg/String, not "
        'std_msgs/msg/Int32; nothing will arrive until a matching publisher '
        'appears\n'
    )


def test_a_jazzy_name_at_a_kilted_turtlesim_names_ros_distro(
    run: Callable[..., Result], talker: Any, ros_context: Any, topic: str
) -> None:
    from ros2lite.interfaces import get_interface

    pose = get_interface('turtlesim_msgs/msg/Pose')
    talker(topic, 'turtlesim_msgs/msg/Pose', lambda i: pose(x=float(i)))
    wait_until(lambda: has_endpoint(ros_context, topic, 'MP'))
    result = run('topic', 'echo', topic, 'turtlesim/msg/Pose', '--timeout', '0.5')
    assert (result.code, result.out) == (0, '')
    assert result.err == (
        f"WARNING: topic '{topic}' is published as turtlesim_msgs/msg/Pose, not "
        'turtlesim/msg/Pose; nothing will arrive until a matching publisher appears (the '
        'node runs with ROS_DISTRO=kilted, which names them turtlesim_msgs: type '
        'turtlesim_msgs/msg/Pose, or start it without ROS_DISTRO=kilted)\n'
    )


def test_csv_and_flow_style(run: Callable[..., Result], talker: Any, topic: str) -> None:
    # as ros2cli prints them: an empty sequence in first place leaves no CSV column, and
    # --flow-style flows the sequences only, mappings stay in block style
    arr = get_interface('std_msgs/msg/Int32MultiArray')
    talker(topic, 'std_msgs/msg/Int32MultiArray', lambda i: arr(data=[1, 2, i]))
    csv = run('topic', 'echo', topic, '--csv', '--once', *LIMIT)
    assert csv.code == 0 and re.fullmatch(r'0,1,2,\d+\n', csv.out), csv.out
    flow = run('topic', 'echo', topic, '--flow-style', '--once', *LIMIT)
    assert re.fullmatch(
        r'layout:\n  dim: \[\]\n  data_offset: 0\ndata: \[1, 2, \d+\]\n---\n', flow.out
    ), flow.out


def test_field_selection(run: Callable[..., Result], talker: Any, topic: str) -> None:
    twist = get_interface('geometry_msgs/msg/Twist')
    vec = get_interface('geometry_msgs/msg/Vector3')
    talker(topic, 'geometry_msgs/msg/Twist', lambda i: twist(linear=vec(x=2.0), angular=vec(z=1.8)))
    nested = run('topic', 'echo', topic, '--field', 'linear', '--once', *LIMIT)
    assert nested.out == 'x: 2.0\ny: 0.0\nz: 0.0\n---\n'
    leaf = run('topic', 'echo', topic, '--field', 'angular.z', '--once', *LIMIT)
    assert leaf.out == '1.8\n---\n'
    bad = run('topic', 'echo', topic, '--field', 'linear.w', '--once', *LIMIT)
    assert bad.code == 1
    assert bad.err == "Invalid field 'linear.w': 'Vector3' object has no attribute 'w'\n"


def test_field_value_without_names_is_rejected(run: Callable[..., Result], topic: str) -> None:
    result = run('topic', 'echo', topic, 'std_msgs/msg/String', '--field', '.')
    assert (result.code, result.err) == (1, "Invalid field value '.'\n")


def test_array_options(run: Callable[..., Result], talker: Any, topic: str) -> None:
    arr = get_interface('std_msgs/msg/Float64MultiArray')
    talker(
        topic, 'std_msgs/msg/Float64MultiArray', lambda i: arr(data=[float(k) for k in range(6)])
    )
    no_arr = run('topic', 'echo', topic, '--no-arr', '--once', *LIMIT)
    assert no_arr.out == (
        "layout:\n"
        "  dim: '<sequence type: std_msgs/msg/MultiArrayDimension, length: 0>'\n"
        "  data_offset: 0\ndata: '<sequence type: double, length: 6>'\n---\n"
    )
    short = run('topic', 'echo', topic, '-l', '2', '--field', 'data', '--once', *LIMIT)
    assert short.out == "array('d', [0.0, 1.0, 2.0, 3.0, 4.0, 5.0])\n---\n"
    truncated = run('topic', 'echo', topic, '-l', '2', '--once', *LIMIT)
    assert truncated.out.endswith("data:\n- 0.0\n- 1.0\n- '...'\n---\n"), truncated.out


def test_string_options(run: Callable[..., Result], talker: Any, topic: str) -> None:
    talker(topic, 'std_msgs/msg/String', lambda i: String(data='x' * 140))
    default = run('topic', 'echo', topic, '--once', *LIMIT)
    assert default.out == f'data: {"x" * 128}...\n---\n'
    full = run('topic', 'echo', topic, '-f', '--once', *LIMIT)
    assert full.out == f'data: {"x" * 140}\n---\n'
    no_str = run('topic', 'echo', topic, '--no-str', '--once', *LIMIT)
    assert no_str.out == "data: '<string length: <140>>'\n---\n"


def test_raw_prints_the_cdr_bytes(run: Callable[..., Result], talker: Any, topic: str) -> None:
    msg = String(data='raw me')
    talker(topic, 'std_msgs/msg/String', lambda i: msg)
    result = run('topic', 'echo', topic, '--raw', '--once', *LIMIT)
    assert result.out == f'{serialize(msg)!r}\n---\n'


def test_filter_expression(run: Callable[..., Result], talker: Any, topic: str) -> None:
    talker(topic, 'std_msgs/msg/Int32', lambda i: Int32(data=i), rate=100)
    result = run(
        'topic', 'echo', topic, '--filter', 'm.data % 7 == 3 and m.data > 2', '--once', *LIMIT
    )
    match = re.fullmatch(r'data: (\d+)\n---\n', result.out)
    assert match and int(match.group(1)) % 7 == 3, result.out


def test_message_info(run: Callable[..., Result], talker: Any, topic: str) -> None:
    talker(topic, 'std_msgs/msg/String', hello)
    yaml_out = run('topic', 'echo', topic, '-i', '--once', *LIMIT).out
    match = re.fullmatch(
        r'publication_sequence_number: (\d+)\nreceived_timestamp: (\d+)\n'
        r'reception_sequence_number: 0\nsource_timestamp: (\d+)\n---\n'
        r"data: 'Hello World: (\d+)'\n---\n",
        yaml_out,
    )
    assert match, yaml_out
    seq, received, source, number = map(int, match.groups())
    assert seq == number  # one put per message, numbered from 1
    assert 0 <= received - source < 5 * 10**9
    csv_out = run('topic', 'echo', topic, '-i', '--csv', '--once', *LIMIT).out
    match = re.fullmatch(r'(\d+),(\d+),(\d+),0,Hello World: (\d+)\n', csv_out)
    assert match and match.group(3) == match.group(4), csv_out


def test_clear_screen(run: Callable[..., Result], talker: Any, topic: str) -> None:
    talker(topic, 'std_msgs/msg/String', hello)
    result = run('topic', 'echo', topic, '-c', '--once', *LIMIT)
    assert result.out.startswith('\x1b[H\x1b[2J')
    assert HELLO.fullmatch(result.out[len('\x1b[H\x1b[2J') :])


def test_node_name_option(processes: Any, ros_context: Any, topic: str) -> None:
    proc = processes.cli('topic', 'echo', '-n', 'my_echo', topic, 'std_msgs/msg/String')
    wait_until(lambda: has_endpoint(ros_context, topic, 'MS', 'my_echo'))
    processes.stop(proc)


def test_reliability_fallback_warning(run: Callable[..., Result], talker: Any, topic: str) -> None:
    talker(topic, 'std_msgs/msg/String', hello, qos=QoSProfile(depth=10))
    talker(
        topic,
        'std_msgs/msg/String',
        hello,
        node_name='best_effort',
        qos=QoSProfile(reliability=ReliabilityPolicy.BEST_EFFORT, depth=10),
    )
    result = run('topic', 'echo', topic, '--once', *LIMIT)
    assert result.code == 0
    warning = (
        'Some, but not all, publishers are offering QoSReliabilityPolicy.RELIABLE. '
        'Falling back to QoSReliabilityPolicy.BEST_EFFORT as it will connect to all '
        'publishers\n'
    )
    assert result.out.startswith(warning) and HELLO.fullmatch(result.out[len(warning) :])
    # an explicit --qos-* choice skips the matching (and its warning)
    explicit = run('topic', 'echo', topic, '--qos-reliability', 'best_effort', '--once', *LIMIT)
    assert HELLO.fullmatch(explicit.out), explicit.out


def test_durability_fallback_warning(run: Callable[..., Result], talker: Any, topic: str) -> None:
    talker(topic, 'std_msgs/msg/String', hello, qos=QoSProfile(depth=10))
    talker(
        topic,
        'std_msgs/msg/String',
        hello,
        node_name='latched',
        qos=QoSProfile(durability=DurabilityPolicy.TRANSIENT_LOCAL, depth=10),
    )
    result = run('topic', 'echo', topic, '--once', *LIMIT)
    warning = (
        'Some, but not all, publishers are offering QoSDurabilityPolicy.TRANSIENT_LOCAL. '
        'Falling back to QoSDurabilityPolicy.VOLATILE as it will connect to all '
        'publishers\n'
    )
    assert result.out.startswith(warning) and HELLO.fullmatch(result.out[len(warning) :])


def test_transient_local_late_joiner(
    run: Callable[..., Result], talker: Any, ros_context: Any, topic: str
) -> None:
    latched = QoSProfile(durability=DurabilityPolicy.TRANSIENT_LOCAL, depth=1)
    t = talker(topic, 'std_msgs/msg/String', lambda i: String(data='latched'), qos=latched, count=1)
    wait_until(lambda: t.sent == 1)
    # every publisher is transient-local, so echo asks for it and gets the stored sample
    matched = run('topic', 'echo', topic, '--once', *LIMIT)
    assert (matched.code, matched.out) == (0, 'data: latched\n---\n')
    explicit = run(
        'topic',
        'echo',
        topic,
        '--qos-durability',
        'transient_local',
        '--qos-reliability',
        'reliable',
        '--once',
        *LIMIT,
    )
    assert explicit.out == 'data: latched\n---\n'
    volatile = run('topic', 'echo', topic, '--qos-durability', 'volatile', '--timeout', '0.5')
    assert (volatile.code, volatile.out) == (0, '')


def test_lost_messages_are_reported(run: Callable[..., Result], talker: Any, topic: str) -> None:
    def gappy(i: int) -> Any:
        if i % 5 == 0:
            t.pub._seq += 3  # as if three samples were lost on the way
        return String(data=str(i))

    t = talker(topic, 'std_msgs/msg/String', gappy, rate=20)
    result = run('topic', 'echo', topic, '--timeout', '0.8')
    lost = re.findall(
        r'A message was lost!!!\n\ttotal count change:(\d+)\n'
        r'\ttotal count: (\d+)---\n',
        result.out,
    )
    assert lost, result.out
    assert all(change == '3' for change, _ in lost)
    assert [int(total) for _, total in lost] == [3 * k for k in range(1, len(lost) + 1)]
    quiet = run('topic', 'echo', topic, '--no-lost-messages', '--timeout', '0.8')
    assert 'lost' not in quiet.out and 'data:' in quiet.out
