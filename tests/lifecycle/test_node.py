"""LifecycleNode: transitions and callbacks, the publisher that waits for `active`, and the
services and transition events as another node sees them over the router."""

from __future__ import annotations

import threading
from collections.abc import Iterator
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface
from ros2lite.lifecycle import (
    InvalidTransitionError,
    LifecycleNode,
    LifecycleState,
    TransitionCallbackReturn,
)
from ros2lite.node import Node
from tests.spinning import wait_until

String = get_interface('std_msgs/msg/String')
Transition = get_interface('lifecycle_msgs/msg/Transition')
ChangeState = get_interface('lifecycle_msgs/srv/ChangeState')
GetState = get_interface('lifecycle_msgs/srv/GetState')
GetAvailableStates = get_interface('lifecycle_msgs/srv/GetAvailableStates')
GetAvailableTransitions = get_interface('lifecycle_msgs/srv/GetAvailableTransitions')
TransitionEvent = get_interface('lifecycle_msgs/msg/TransitionEvent')

SUCCESS, FAILURE, ERROR = (
    TransitionCallbackReturn.SUCCESS,
    TransitionCallbackReturn.FAILURE,
    TransitionCallbackReturn.ERROR,
)


def label(node: LifecycleNode) -> str:
    return node.current_state.label


def test_transitions_and_callbacks(ros_context: Any) -> None:
    calls: list[tuple[str, LifecycleState]] = []

    class Recorder(LifecycleNode):
        def on_configure(self, state: LifecycleState) -> TransitionCallbackReturn:
            calls.append(('configure', state))
            return SUCCESS

        def on_cleanup(self, state: LifecycleState) -> TransitionCallbackReturn:
            calls.append(('cleanup', state))
            return SUCCESS

    node = Recorder('lc_recorder', context=ros_context, enable_communication_interface=False)
    try:
        assert label(node) == 'unconfigured'
        for _ in range(3):  # back and forth, as often as asked
            assert node.trigger_configure() == SUCCESS and label(node) == 'inactive'
            assert node.trigger_cleanup() == SUCCESS and label(node) == 'unconfigured'
        # callbacks get the state the transition started from
        assert calls[:2] == [
            ('configure', LifecycleState('unconfigured', 1)),
            ('cleanup', LifecycleState('inactive', 2)),
        ]
        node.trigger_configure()
        assert node.trigger_activate() == SUCCESS and label(node) == 'active'
        with pytest.raises(InvalidTransitionError):
            node.trigger_cleanup()  # not from active
        assert label(node) == 'active'
        assert node.trigger_shutdown() == SUCCESS and label(node) == 'finalized'
        with pytest.raises(InvalidTransitionError):
            node.trigger_shutdown()
    finally:
        node.destroy_node()


def test_failure_error_and_recovery(ros_context: Any) -> None:
    answers: dict[str, Any] = {'configure': FAILURE, 'error': SUCCESS}

    class Flaky(LifecycleNode):
        def on_configure(self, state: LifecycleState) -> TransitionCallbackReturn:
            answer = answers['configure']
            if isinstance(answer, Exception):
                raise answer
            return answer  # type: ignore[no-any-return]

        def on_error(self, state: LifecycleState) -> TransitionCallbackReturn:
            return answers['error']  # type: ignore[no-any-return]

    node = Flaky('lc_flaky', context=ros_context, enable_communication_interface=False)
    try:
        # FAILURE goes back where it started
        assert node.trigger_configure() == FAILURE and label(node) == 'unconfigured'
        # ERROR runs on_error: SUCCESS recovers to unconfigured...
        answers['configure'] = ERROR
        assert node.trigger_configure() == ERROR and label(node) == 'unconfigured'
        # ...an exception counts as ERROR, and anything but SUCCESS from on_error finalizes
        answers['configure'] = RuntimeError('boom')
        answers['error'] = FAILURE
        assert node.trigger_configure() == ERROR and label(node) == 'finalized'
    finally:
        node.destroy_node()

    # a callback that returns something else is an error too; register_callback replaces one
    other = LifecycleNode('lc_other', context=ros_context, enable_communication_interface=False)
    try:
        other.register_callback(10, lambda state: 'yes')  # type: ignore[arg-type,return-value]
        assert other.trigger_configure() == ERROR and label(other) == 'unconfigured'
        with pytest.raises(ValueError):
            other.register_callback(2, lambda state: SUCCESS)  # 2 is a primary state
    finally:
        other.destroy_node()


def test_enable_communication_interface_must_be_bool(ros_context: Any) -> None:
    with pytest.raises(TypeError):
        LifecycleNode('lc_bad', context=ros_context, enable_communication_interface='yes')  # type: ignore[arg-type]
    quiet = LifecycleNode('lc_quiet', context=ros_context, enable_communication_interface=False)
    try:
        assert not hasattr(quiet, '_service_change_state')
        served = [s.srv_name for s in quiet.services]
        assert served and not [n for n in served if 'state' in n or 'transition' in n]
        assert not any('transition' in p.topic_name for p in quiet.publishers)
    finally:
        quiet.destroy_node()


@pytest.fixture
def spun(ros_context: Any) -> Iterator[tuple[LifecycleNode, Node]]:
    """A lifecycle node and a plain client node, both spun by one executor thread."""
    managed = LifecycleNode('lc_served', context=ros_context, enable_rosout=False)
    client = Node('lc_client', context=ros_context, enable_rosout=False)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(managed)
    executor.add_node(client)
    thread = threading.Thread(target=executor.spin, daemon=True)
    thread.start()
    try:
        yield managed, client
    finally:
        executor.shutdown()
        thread.join(timeout=5)
        managed.destroy_node()
        client.destroy_node()


def test_services_and_events_over_the_wire(spun: tuple[LifecycleNode, Node]) -> None:
    managed, node = spun
    events: list[tuple[str, str]] = []
    node.create_subscription(
        TransitionEvent,
        '/lc_served/transition_event',
        lambda m: events.append((m.start_state.label, m.goal_state.label)),
        10,
    )
    clients = {
        name: node.create_client(srv, f'/lc_served/{name}')
        for name, srv in (
            ('change_state', ChangeState),
            ('get_state', GetState),
            ('get_available_states', GetAvailableStates),
            ('get_available_transitions', GetAvailableTransitions),
            ('get_transition_graph', GetAvailableTransitions),
        )
    }
    for client in clients.values():
        assert client.wait_for_service(timeout_sec=10)
    wait_until(lambda: node.count_publishers('/lc_served/transition_event') == 1)
    wait_until(lambda: managed.count_subscribers('/lc_served/transition_event') == 1)

    def call(name: str, **fields: Any) -> Any:
        return clients[name].call(clients[name].srv_type.Request(**fields), timeout_sec=10)

    assert call('get_state').current_state.label == 'unconfigured'
    states = call('get_available_states').available_states
    assert [s.label for s in states] == [
        'unknown', 'unconfigured', 'inactive', 'active', 'finalized', 'configuring',
        'cleaningup', 'shuttingdown', 'activating', 'deactivating', 'errorprocessing',
    ]  # fmt: skip
    assert len(call('get_transition_graph').available_transitions) == 25
    # by id, then by label; a transition the state does not offer is refused
    configure = Transition(id=Transition.TRANSITION_CONFIGURE)
    assert call('change_state', transition=configure).success
    offered = call('get_available_transitions').available_transitions
    assert [(d.transition.label, d.transition.id) for d in offered] == [
        ('cleanup', 2),
        ('activate', 3),
        ('shutdown', 6),
    ]
    assert not call('change_state', transition=Transition(label='deactivate')).success
    assert not call('change_state', transition=Transition(id=42)).success
    assert call('change_state', transition=Transition(label='activate')).success
    assert label(managed) == 'active'
    # rcl's events: into the transition state, then out of it
    wait_until(lambda: len(events) == 4)
    assert events == [
        ('unconfigured', 'configuring'),
        ('configuring', 'inactive'),
        ('inactive', 'activating'),
        ('activating', 'active'),
    ]


def test_lifecycle_publisher_silent_until_active(spun: tuple[LifecycleNode, Node]) -> None:
    managed, node = spun
    got: list[str] = []
    node.create_subscription(String, '/lc_data', lambda m: got.append(m.data), 10)
    pub = managed.create_lifecycle_publisher(String, '/lc_data', 10)
    wait_until(lambda: pub.get_subscription_count() == 1)
    managed.trigger_configure()
    assert not pub.is_activated
    pub.publish(String(data='while inactive'))
    managed.trigger_activate()
    assert pub.is_activated
    pub.publish(String(data='while active'))
    # one reliable publisher keeps its order: had the first been sent it would be here first
    wait_until(lambda: got)
    assert got == ['while active']
    managed.trigger_deactivate()
    pub.publish(String(data='deactivated'))
    managed.trigger_activate()
    pub.publish(String(data='active again'))
    wait_until(lambda: len(got) == 2)
    assert got == ['while active', 'active again']
    managed.destroy_lifecycle_publisher(pub)
    assert pub not in managed.publishers
