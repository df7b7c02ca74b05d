"""The lifecycle demo as ROS runs it: `lifecycle_py lifecycle_talker` and `lifecycle
lifecycle_listener` as processes, the talker driven through its whole life by the CLI."""

from __future__ import annotations

import re
import threading
from typing import Any

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from tests.bundled.test_demo_nodes_py import log_line
from tests.cli.conftest import run_process
from tests.spinning import spin_until, wait_until

String = get_interface('std_msgs/msg/String')


def test_talker_through_its_life(ros_context: Any, processes: Any) -> None:
    talker = processes.cli('run', 'lifecycle_py', 'lifecycle_talker')
    listener = processes.cli('run', 'lifecycle', 'lifecycle_listener')
    heard: list[str] = []
    lines: list[str] = []
    reader = threading.Thread(target=lambda: lines.extend(listener.stderr), daemon=True)
    reader.start()
    observer = Node('lc_demo_observer', context=ros_context, enable_rosout=False)
    observer.create_subscription(String, '/lifecycle_chatter', lambda m: heard.append(m.data), 10)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(observer)
    try:
        wait_until(lambda: run_process('lifecycle', 'nodes').out == '/lc_talker\n', timeout=20)
        wait_until(lambda: observer.count_subscribers('/lc_talker/transition_event') == 1)
        assert run_process('lifecycle', 'get', '/lc_talker').out == 'unconfigured [1]\n'
        for transition in ('configure', 'activate'):
            assert run_process('lifecycle', 'set', '/lc_talker', transition).out == (
                'Transitioning successful\n'
            )
        spin_until(executor, lambda: heard, timeout=15)
        assert re.fullmatch(r'Lifecycle HelloWorld #\d+', heard[0])
        wait_until(lambda: any('data_callback: Lifecycle HelloWorld #' in x for x in lines))
        for transition in ('deactivate', 'cleanup', 'shutdown'):
            assert run_process('lifecycle', 'set', '/lc_talker', transition).code == 0
        assert run_process('lifecycle', 'get', '/lc_talker').out == 'finalized [4]\n'
    finally:
        executor.shutdown()
        observer.destroy_node()
    _out, talker_err = processes.stop(talker)
    processes.stop(listener)
    reader.join(timeout=5)
    assert talker.returncode == 0 and 'Traceback' not in talker_err
    said = [line for line in talker_err.splitlines() if 'is called' in line]
    for line, callback in zip(
        said, ['configure', 'activate', 'deactivate', 'cleanup', 'shutdown'], strict=True
    ):
        assert re.fullmatch(log_line('lc_talker', re.escape(f'on_{callback}() is called.')), line)
    assert any(
        'Lifecycle publisher is active. Publishing: [Lifecycle HelloWorld #' in x
        for x in talker_err.splitlines()
    )
    transitions = [x.rstrip('\n').split(': ', 1)[1] for x in lines if 'notify callback' in x]
    assert transitions[:4] == [
        'notify callback: Transition from state unconfigured to configuring',
        'notify callback: Transition from state configuring to inactive',
        'notify callback: Transition from state inactive to activating',
        'notify callback: Transition from state activating to active',
    ]
    assert transitions[-1] == 'notify callback: Transition from state shuttingdown to finalized'
