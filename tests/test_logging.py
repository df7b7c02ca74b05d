"""Node logging: rcutils' console line on stderr, levels, the once/skip/throttle filters, and
`rcl_interfaces/msg/Log` on `/rosout` (transient local, so a late subscriber still gets it)."""

from __future__ import annotations

import re
import time
from collections.abc import Iterator
from typing import Any

import pytest

from ros2lite import logging as rlog
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import ROSOUT_QOS, Node
from tests.spinning import spin_for, spin_until

LINE = re.compile(r'^\[(DEBUG|INFO|WARN|ERROR|FATAL)\] \[(\d+)\.(\d{9})\] \[([\w.]+)\]: (.*)$')


@pytest.fixture(autouse=True)
def clean_levels(monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    for var in (
        'RCUTILS_CONSOLE_OUTPUT_FORMAT',
        'RCUTILS_LOGGING_USE_STDOUT',
        'RCUTILS_COLORIZED_OUTPUT',
    ):
        monkeypatch.delenv(var, raising=False)
    saved = dict(rlog._levels)
    yield
    rlog._levels.clear()
    rlog._levels.update(saved)


def test_console_format(ros_context: Any, capsys: pytest.CaptureFixture[str]) -> None:
    node = Node('talker', context=ros_context)
    before = time.time()
    assert node.get_logger().info('Publishing: "Hello World: 0"')
    after = time.time()
    out, err = capsys.readouterr()
    assert out == ''
    m = LINE.match(err.rstrip('\n'))
    assert m, err
    assert m.group(1) == 'INFO' and m.group(4) == 'talker'
    assert m.group(5) == 'Publishing: "Hello World: 0"'
    assert before - 0.01 <= int(m.group(2)) + int(m.group(3)) / 1e9 <= after + 0.01


def test_severities_and_levels(ros_context: Any, capsys: pytest.CaptureFixture[str]) -> None:
    logger = Node('levels', namespace='/ns', context=ros_context).get_logger()
    assert logger.name == 'ns.levels'
    assert logger.debug('hidden') is False
    logger.warn('w')
    logger.warning('w2')
    logger.error('e')
    logger.fatal('f')
    err = capsys.readouterr().err.splitlines()
    assert [LINE.match(x).group(1) for x in err] == ['WARN', 'WARN', 'ERROR', 'FATAL']  # type: ignore[union-attr]
    logger.set_level(rlog.DEBUG)
    assert logger.get_effective_level() == rlog.DEBUG
    assert logger.get_child('child').is_enabled_for(rlog.DEBUG)  # children inherit
    assert logger.debug('shown')
    assert '[DEBUG]' in capsys.readouterr().err


def test_log_level_argument(ros_context: Any, capsys: pytest.CaptureFixture[str]) -> None:
    node = Node(
        'verbose', context=ros_context, cli_args=['--ros-args', '--log-level', 'verbose:=debug']
    )
    assert node.get_logger().debug('dbg')
    quiet = Node('quiet', context=ros_context)
    assert not quiet.get_logger().debug('nope')
    assert capsys.readouterr().err.count('[DEBUG]') == 1


def test_filters(capsys: pytest.CaptureFixture[str]) -> None:
    logger = rlog.get_logger('filters')
    results = [logger.info('once', once=True) for _ in range(3)]
    assert results == [True, False, False]
    results = [logger.info('skip', skip_first=True) for _ in range(3)]
    assert results == [False, True, True]
    results = [logger.info('throttled', throttle_duration_sec=10) for _ in range(3)]
    assert results == [True, False, False]
    assert capsys.readouterr().err.count('\n') == 4


def test_output_format_and_stdout(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv(
        'RCUTILS_CONSOLE_OUTPUT_FORMAT', '{severity}|{name}|{function_name}|{line_number}|{message}'
    )
    monkeypatch.setenv('RCUTILS_LOGGING_USE_STDOUT', '1')
    rlog.get_logger('fmt').warn('hi')
    out, err = capsys.readouterr()
    assert err == ''
    severity, name, function, line, message = out.strip().split('|')
    assert (severity, name, function, message) == (
        'WARN',
        'fmt',
        'test_output_format_and_stdout',
        'hi',
    )
    assert int(line) > 0


def test_rosout_message_reaches_a_late_subscriber(
    ros_context: Any, capsys: pytest.CaptureFixture[str]
) -> None:
    from ros2lite.context import Context

    node = Node('chatty', namespace='/logs', context=ros_context)
    node.get_logger().warn('remember me')
    line_no = _this_line() - 1
    capsys.readouterr()
    other = Context().init([])
    try:
        reader = Node('reader', context=other, enable_rosout=False)
        got: list[Any] = []
        reader.create_subscription('rcl_interfaces/msg/Log', '/rosout', got.append, ROSOUT_QOS)
        ex = SingleThreadedExecutor(context=other)
        ex.add_node(reader)
        spin_until(ex, lambda: any(m.name == 'logs.chatty' for m in got))
        log = next(m for m in got if m.name == 'logs.chatty')
        assert log.msg == 'remember me'
        assert log.level == 30
        assert log.function == 'test_rosout_message_reaches_a_late_subscriber'
        assert log.file.endswith('test_logging.py') and log.line == line_no
        assert abs(log.stamp.sec + log.stamp.nanosec / 1e9 - time.time()) < 10
        # and live messages follow
        node.get_logger().info('live')
        spin_until(ex, lambda: any(m.msg == 'live' for m in got))
    finally:
        other.shutdown()


def test_rosout_can_be_disabled(ros_context: Any) -> None:
    node = Node('silent', context=ros_context, enable_rosout=False)
    assert all(p.topic_name != '/rosout' for p in node.publishers)
    ex = SingleThreadedExecutor(context=ros_context)
    ex.add_node(node)
    got: list[Any] = []
    node.create_subscription(
        'rcl_interfaces/msg/Log',
        '/rosout',
        lambda m: got.append(m) if m.name == 'silent' else None,
        ROSOUT_QOS,
    )
    node.get_logger().info('console only')
    spin_for(ex, 0.3)
    assert got == []


def _this_line() -> int:
    import inspect

    frame = inspect.currentframe()
    assert frame is not None and frame.f_back is not None
    return frame.f_back.f_lineno


def test_direct_log_call_reports_its_caller(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.setenv(
        'RCUTILS_CONSOLE_OUTPUT_FORMAT',
        '{function_name}|{line_number}|{date_time_with_ms}|{time_as_nanoseconds}',
    )
    rlog.get_logger('direct').log('x', rlog.WARN)
    line_no = _this_line() - 1
    function, line, date_time, nanos = capsys.readouterr().err.strip().split('|')
    assert (function, int(line)) == ('test_direct_log_call_reports_its_caller', line_no)
    assert re.fullmatch(r'\d{4}-\d\d-\d\d \d\d:\d\d:\d\d\.\d{3}', date_time)
    assert abs(int(nanos) - time.time_ns()) < 10_000_000_000


def test_logging_cost_does_not_grow_with_stack_depth(capsys: pytest.CaptureFixture[str]) -> None:
    logger = rlog.get_logger('cheap')

    def deep(n: int) -> float:
        if n:
            return deep(n - 1)
        start = time.perf_counter()
        for _ in range(200):
            logger.info('x')
        return time.perf_counter() - start

    assert deep(60) < 0.2  # walking the stack per call took ~1 ms each here
    capsys.readouterr()


def test_severity_hierarchy_and_clearing() -> None:
    from ros2lite.logging import LoggingSeverity as S

    root = rlog._root_logger
    parent = rlog.get_logger('tree')
    child = parent.get_child('leaf')
    assert child.name == 'tree.leaf'
    root.set_level(S.WARN)
    assert child.get_effective_level() == S.WARN  # from the root, through the parent
    parent.set_level(S.ERROR)
    assert child.get_effective_level() == S.ERROR
    child.set_level(S.DEBUG)
    assert (parent.get_effective_level(), child.get_effective_level()) == (S.ERROR, S.DEBUG)
    child.set_level(S.UNSET)  # back to inheriting
    assert child.get_effective_level() == S.ERROR
    rlog.clear_config()
    assert child.get_effective_level() == S.INFO
    assert rlog.get_logging_severity_from_string('warn') == S.WARN
    with pytest.raises(RuntimeError):
        rlog.get_logging_severity_from_string('loud')
    with pytest.raises(ValueError, match='must not be empty'):
        rlog.get_logger('')
    with pytest.raises(ValueError, match='must not be empty'):
        parent.get_child('')


def test_a_call_site_keeps_its_arguments(capsys: pytest.CaptureFixture[str]) -> None:
    logger = rlog.get_logger('site')
    with pytest.raises(TypeError, match='not one of the recognized'):
        logger.info('x', sometimes=True)
    with pytest.raises(TypeError, match="required parameter 'throttle_duration_sec'"):
        logger.info('x', throttle_time_source_type=None)
    with pytest.raises(ValueError, match='severity cannot be changed'):
        for severity in (rlog.INFO, rlog.WARN):
            logger.log('x', severity)
    # skip_first is applied before once, throttle before both
    assert [logger.info('y', skip_first=True, once=True) for _ in range(3)] == [
        False,
        True,
        False,
    ]
    capsys.readouterr()


def test_throttle_on_a_ros_clock(capsys: pytest.CaptureFixture[str]) -> None:
    from ros2lite.clock import ROSClock
    from ros2lite.time import ClockType, Time

    clock = ROSClock()
    clock._set_ros_time_is_active(True)
    logger = rlog.get_logger('sim')
    seen = []
    for second in range(5):
        seen.append(logger.info('tick', throttle_duration_sec=2, throttle_time_source_type=clock))
        clock.set_ros_time_override(Time(seconds=second + 1, clock_type=ClockType.ROS_TIME))
    assert seen == [False, False, True, False, True]  # ROS time starts at 0
    capsys.readouterr()


def test_logging_directory(monkeypatch: pytest.MonkeyPatch, tmp_path: Any) -> None:
    monkeypatch.delenv('ROS_LOG_DIR', raising=False)
    monkeypatch.setenv('ROS_HOME', str(tmp_path))
    assert rlog.get_logging_directory() == tmp_path / 'log'
    monkeypatch.delenv('ROS_HOME')
    monkeypatch.setenv('HOME', '/home/someone')
    assert str(rlog.get_logging_directory()) == '/home/someone/.ros/log'


def test_rosout_and_stdout_switches(ros_router: str, capsys: pytest.CaptureFixture[str]) -> None:
    from ros2lite.context import Context

    ctx = Context().init(['--ros-args', '--disable-rosout-logs', '--disable-stdout-logs'])
    try:
        node = Node('quiet_everywhere', context=ctx)
        assert node._rosout is None
        assert node.get_logger().info('nowhere to be seen') is True
        assert capsys.readouterr().err == ''
    finally:
        rlog.set_console_output(True)
        ctx.shutdown()
