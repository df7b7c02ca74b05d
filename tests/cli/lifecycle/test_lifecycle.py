"""`lifecycle nodes|list|get|set` against managed nodes spun in the test process."""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.lifecycle import LifecycleNode, LifecycleState, TransitionCallbackReturn
from ros2lite.node import Node
from tests.cli.conftest import Result
from tests.spinning import wait_until


class Stubborn(LifecycleNode):
    """Refuses to activate."""

    def on_activate(self, state: LifecycleState) -> TransitionCallbackReturn:
        return TransitionCallbackReturn.FAILURE


@pytest.fixture
def managed(ros_context: Any) -> Iterator[dict[str, LifecycleNode]]:
    nodes: dict[str, Any] = {
        'test_lc': LifecycleNode('test_lc', context=ros_context, enable_rosout=False),
        '_hidden_lc': LifecycleNode('_hidden_lc', context=ros_context, enable_rosout=False),
        'stubborn': Stubborn('stubborn', context=ros_context, enable_rosout=False),
    }
    plain = Node('not_managed', context=ros_context, enable_rosout=False)
    executor = SingleThreadedExecutor(context=ros_context)
    for node in [*nodes.values(), plain]:
        executor.add_node(node)
    thread = threading.Thread(target=executor.spin, daemon=True)
    thread.start()
    wait_until(
        lambda: (
            {'/test_lc/get_state', '/_hidden_lc/get_state', '/stubborn/get_state'}
            <= {name for name, _ in plain.get_service_names_and_types()}
        ),
        timeout=10,
    )
    try:
        yield nodes
    finally:
        executor.shutdown()
        thread.join(timeout=5)
        for node in [*nodes.values(), plain]:
            node.destroy_node()


Run = Callable[..., Result]


def test_nodes(run: Run, managed: dict[str, LifecycleNode]) -> None:
    assert run('lifecycle', 'nodes').out == '/stubborn\n/test_lc\n'
    assert run('lifecycle', 'nodes', '-a').out == '/_hidden_lc\n/stubborn\n/test_lc\n'
    assert run('lifecycle', 'nodes', '-a', '-c').out == '3\n'


def test_get(run: Run, managed: dict[str, LifecycleNode]) -> None:
    assert run('lifecycle', 'get', '/test_lc').out == 'unconfigured [1]\n'
    assert run('lifecycle', 'get', 'test_lc').out == 'unconfigured [1]\n'  # made absolute
    assert run('lifecycle', 'get').out == (
        '/stubborn: unconfigured [1]\n/test_lc: unconfigured [1]\n'
    )
    hidden = run('lifecycle', 'get', '/_hidden_lc')
    assert (hidden.code, hidden.err) == (1, 'Node not found\n')
    shown = run('lifecycle', 'get', '--include-hidden-nodes', '/_hidden_lc', '--timeout', '5')
    assert (shown.code, shown.out) == (0, 'unconfigured [1]\n')
    plain = run('lifecycle', 'get', '/not_managed')
    assert (plain.code, plain.err) == (1, 'Node not found\n')


def test_list(run: Run, managed: dict[str, LifecycleNode]) -> None:
    assert run('lifecycle', 'list', '/test_lc').out == (
        '- configure [1]\n\tStart: unconfigured\n\tGoal: configuring\n'
        '- shutdown [5]\n\tStart: unconfigured\n\tGoal: shuttingdown\n'
    )
    graph = run('lifecycle', 'list', '/test_lc', '-a').out.splitlines()
    assert len(graph) == 25 * 3
    assert graph[:6] == [
        '- configure [1]',
        '\tStart: unconfigured',
        '\tGoal: configuring',
        '- transition_success [10]',
        '\tStart: configuring',
        '\tGoal: inactive',
    ]
    assert graph[-3:] == [
        '- transition_error [62]',
        '\tStart: errorprocessing',
        '\tGoal: finalized',
    ]
    assert run('lifecycle', 'list', '_hidden_lc').err == 'Node not found\n'


def test_set_by_label_and_id(run: Run, managed: dict[str, LifecycleNode]) -> None:
    node = managed['test_lc']
    done = run('lifecycle', 'set', '/test_lc', 'configure')
    assert (done.code, done.out) == (0, 'Transitioning successful\n')
    assert node.current_state.label == 'inactive'
    assert run('lifecycle', 'set', '/test_lc', '3').out == 'Transitioning successful\n'
    assert node.current_state.label == 'active'
    assert run('lifecycle', 'get', '/test_lc').out == 'active [3]\n'
    # an illegal transition is refused before anything is sent
    illegal = run('lifecycle', 'set', '/test_lc', 'configure')
    assert illegal.code == 1
    assert illegal.err == (
        'Unknown transition requested, available ones are:\n- deactivate [4]\n- shutdown [7]\n'
    )
    assert node.current_state.label == 'active'
    hidden = run('lifecycle', 'set', '/_hidden_lc', 'configure')
    assert (hidden.code, hidden.err) == (1, 'Node not found\n')
    assert run('lifecycle', 'set', '--include-hidden-nodes', '/_hidden_lc', 'configure').code == 0
    assert managed['_hidden_lc'].current_state.label == 'inactive'


def test_set_refused_by_the_node(run: Run, managed: dict[str, LifecycleNode]) -> None:
    run('lifecycle', 'set', '/stubborn', 'configure')
    refused = run('lifecycle', 'set', '/stubborn', 'activate')
    # as ros2cli: the failure is reported on stderr, the exit status stays 0
    assert (refused.code, refused.out, refused.err) == (0, '', 'Transitioning failed\n')
    assert managed['stubborn'].current_state.label == 'inactive'
