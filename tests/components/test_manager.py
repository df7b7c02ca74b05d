"""The container node, driven over the wire through the library's client: what a loaded
node gets from the request, ids, unloading, and the refusals."""

from __future__ import annotations

import re
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from ros2lite.components.manager import ComponentManager
from ros2lite.components.remote import (
    ContainerError,
    LoadedNode,
    RemoteContainer,
    container_node_names,
    parse_assignments,
)
from ros2lite.executors import SingleThreadedExecutor
from ros2lite.graph import snapshot
from ros2lite.node import Node
from tests.components.test_registry import ament_prefix
from tests.spinning import wait_until


@pytest.fixture
def container(
    ros_context: Any, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> Iterator[tuple[ComponentManager, RemoteContainer]]:
    ament_prefix(
        tmp_path,
        'rclpy_components',
        'probe_pkg',
        [
            'probe_pkg::Probe;tests.components.probe:Probe',
            'probe_pkg::Broken;tests.components.probe:Broken',
            'probe_pkg::NotANode;tests.components.probe:not_a_node',
        ],
    )
    monkeypatch.setenv('AMENT_PREFIX_PATH', str(tmp_path))
    manager = ComponentManager('test_container', context=ros_context, enable_rosout=False)
    caller = Node('container_caller', context=ros_context, enable_rosout=False)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(manager)
    thread = threading.Thread(target=executor.spin, daemon=True)
    thread.start()
    wait_until(
        lambda: (
            '/test_container'
            in container_node_names(snapshot(ros_context.session, ros_context.domain_id))
        ),
        timeout=10,
    )
    try:
        yield manager, RemoteContainer(caller, '/test_container', timeout=10)
    finally:
        executor.shutdown()
        thread.join(timeout=5)
        manager.destroy_node()
        caller.destroy_node()


def node_names(ctx: Any) -> set[str]:
    return {
        f'{e.namespace.rstrip("/")}/{e.node_name}' for e in snapshot(ctx.session, ctx.domain_id)
    }


def test_load_list_unload(
    container: tuple[ComponentManager, RemoteContainer], ros_context: Any
) -> None:
    manager, remote = container
    first = remote.load(
        'probe_pkg',
        'probe_pkg::Probe',
        node_name='p1',
        node_namespace='/ns',
        log_level=10,
        remap_rules=['chatter:=/remapped'],
        parameters=parse_assignments(['greeting:=hey']),
        extra_arguments=parse_assignments(['use_intra_process_comms:=true']),
    )
    assert first == LoadedNode(1, '/ns/p1')
    probe: Any = manager.components[1].node
    assert probe.get_parameter('greeting').value == 'hey'
    assert probe.pub.topic_name == '/remapped'
    assert probe.get_logger().get_effective_level() == 10
    assert probe.executor is manager.executor  # it runs with the container
    assert remote.load('probe_pkg', 'probe_pkg::Probe') == LoadedNode(2, '/probe')
    assert remote.list_nodes() == [LoadedNode(1, '/ns/p1'), LoadedNode(2, '/probe')]
    wait_until(lambda: {'/ns/p1', '/probe'} <= node_names(ros_context))

    assert remote.unload(1) is None
    assert remote.unload(1) == 'No node found with unique_id: 1'
    wait_until(lambda: '/ns/p1' not in node_names(ros_context))  # destroyed, not just forgotten
    assert remote.list_nodes() == [LoadedNode(2, '/probe')]
    assert remote.load('probe_pkg', 'probe_pkg::Probe', node_name='p3').unique_id == 3


@pytest.mark.parametrize(
    ('plugin', 'options', 'reason'),
    [
        ('probe_pkg::Nope', {}, 'Failed to find class with the requested plugin name.'),
        (
            'probe_pkg::Broken',
            {},
            'Component constructor threw an exception: RuntimeError: no hardware here',
        ),
        ('probe_pkg::NotANode', {}, "'tests.components.probe:not_a_node' did not build"),
        ('probe_pkg::Probe', {'log_level': 7}, 'Invalid log level 7'),
        (
            'probe_pkg::Probe',
            {'node_name': 'bad name'},
            'Component constructor threw an exception: InvalidNodeNameException',
        ),
        (
            'probe_pkg::Probe',
            {'extra_arguments': ['use_intra_process_comms:=5']},
            "Extra component argument 'use_intra_process_comms' must be a boolean",
        ),
    ],
)
def test_refusals(
    container: tuple[ComponentManager, RemoteContainer],
    plugin: str,
    options: dict[str, Any],
    reason: str,
) -> None:
    manager, remote = container
    if 'extra_arguments' in options:
        options['extra_arguments'] = parse_assignments(options['extra_arguments'])
    with pytest.raises(
        ContainerError, match='^' + re.escape('Failed to load component: ' + reason)
    ):
        remote.load('probe_pkg', plugin, **options)
    assert manager.components == {}
    assert remote.load('probe_pkg', 'probe_pkg::Probe').unique_id == 1  # nothing was used up


def test_bad_assignment() -> None:
    with pytest.raises(ContainerError, match="'greeting' is not in the 'name:=value' form"):
        parse_assignments(['greeting'])


def test_a_failed_load_leaves_no_ghost_node(
    container: tuple[ComponentManager, RemoteContainer], ros_context: Any
) -> None:
    """R-K3: a constructor failing after its node announced itself (here a remap that makes
    the publisher's name invalid) left the node on the graph, unlisted and unreachable."""
    _manager, remote = container
    for _ in range(3):
        with pytest.raises(ContainerError, match='InvalidTopicNameException'):
            remote.load('composition', 'composition::Talker', remap_rules=['chatter:=/a//b'])
    remote.load('probe_pkg', 'probe_pkg::Probe', node_name='after')

    def graph_nodes() -> set[str]:  # the context's own graph cache: no query to miss a token
        return {e.node_name for e in ros_context.graph.entities()}

    wait_until(lambda: 'after' in graph_nodes())
    assert 'talker' not in graph_nodes()
    assert remote.list_nodes() == [LoadedNode(1, '/after')]
