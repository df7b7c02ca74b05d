"""`demo_nodes_py introspection` (Jazzy's: service and client nodes in one process):
introspection that follows their parameters, at start and at run time."""

from __future__ import annotations

from typing import Any

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from tests.cli.conftest import run_process
from tests.spinning import spin_until, wait_until

Event = get_interface('example_interfaces/srv/AddTwoInts_Event')


def test_introspection_follows_the_parameters(ros_context: Any, processes: Any) -> None:
    both = processes.cli(
        'run', 'demo_nodes_py', 'introspection',
        '--ros-args', '-p', 'service_configure_introspection:=contents',
    )  # fmt: skip
    events: list[Any] = []
    observer = Node('introspection_observer', context=ros_context, enable_rosout=False)
    observer.create_subscription(Event, '/add_two_ints/_service_event', events.append, 100)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(observer)
    try:
        # the service reports (with contents), the client does not: only server events
        spin_until(executor, lambda: len(events) >= 4, timeout=30)
        kinds = {e.info.event_type for e in events}
        assert kinds == {1, 2}
        assert all(len(e.request) + len(e.response) == 1 for e in events)
        # switched on at run time through the parameter, metadata only
        wait_until(lambda: '/introspection_client' in run_process('node', 'list').out)
        done = run_process(
            'param', 'set', '/introspection_client', 'client_configure_introspection', 'metadata'
        )
        assert done.out == 'Set parameter successful\n', done.err
        spin_until(executor, lambda: {e.info.event_type for e in events} == {0, 1, 2, 3}, 30)
        client_events = [e for e in events if e.info.event_type in (0, 3)]
        assert all(len(e.request) + len(e.response) == 0 for e in client_events)
        refused = run_process(
            'param', 'set', '/introspection_client', 'client_configure_introspection', 'loud'
        )
        assert 'Setting parameter failed' in refused.err
        assert "must be one of 'disabled', 'metadata', or 'contents'" in refused.err
    finally:
        executor.shutdown()
        observer.destroy_node()
    _out, err = processes.stop(both)
    assert both.returncode == 0 and 'Traceback' not in err
    assert '[introspection_service]: Incoming request\na: 2 b: 3\n' in err
    assert '[introspection_client]: Result of add_two_ints: 5\n' in err
