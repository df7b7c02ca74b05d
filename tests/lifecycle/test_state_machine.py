"""The default state machine as data: rcl_lifecycle's graph, order, ids and labels."""

from __future__ import annotations

import pytest

from ros2lite.interfaces import get_interface
from ros2lite.lifecycle.state_machine import (
    STATES,
    TRANSITIONS,
    InvalidTransitionError,
    StateMachine,
    TransitionCallbackReturn,
)

State = get_interface('lifecycle_msgs/msg/State')
Transition = get_interface('lifecycle_msgs/msg/Transition')


def test_ids_are_lifecycle_msgs_constants() -> None:
    for state_id, label in STATES.items():
        constant = next(k for k, v in vars(State).items() if k.isupper() and v == state_id)
        assert constant.endswith(label.upper()), (constant, label)
    ids = {v for k, v in vars(Transition).items() if k.startswith('TRANSITION_')}
    assert {t.id for t in TRANSITIONS} <= ids
    assert [r.value for r in TransitionCallbackReturn] == [
        Transition.TRANSITION_CALLBACK_SUCCESS,
        Transition.TRANSITION_CALLBACK_FAILURE,
        Transition.TRANSITION_CALLBACK_ERROR,
    ]


def test_graph_in_rcl_order() -> None:
    # the order `ros2 lifecycle list -a` prints for any node on the default state machine
    assert [t.id for t in TRANSITIONS] == [
        1, 10, 11, 12, 2, 20, 21, 22, 3, 30, 31, 32, 4, 40, 41, 42,
        5, 6, 7, 50, 51, 52, 60, 61, 62,
    ]  # fmt: skip
    by_id = {t.id: (STATES[t.start], t.label, STATES[t.goal]) for t in TRANSITIONS}
    assert by_id[11] == ('configuring', 'transition_failure', 'unconfigured')
    assert by_id[41] == ('deactivating', 'transition_failure', 'active')
    assert by_id[51] == ('shuttingdown', 'transition_failure', 'finalized')
    assert by_id[60] == ('errorprocessing', 'transition_success', 'unconfigured')


def test_available_transitions_follow_the_state() -> None:
    sm = StateMachine()
    assert sm.current_state == (1, 'unconfigured')
    assert [(t.label, t.id) for t in sm.available_transitions()] == [
        ('configure', 1),
        ('shutdown', 5),
    ]
    sm.take(sm.transition_by_label('configure'))
    sm.take(sm.transition_by_label('transition_success'))
    assert sm.current_state == (2, 'inactive')
    # one label, three transitions: the current state picks the right 'shutdown'
    assert sm.transition_by_label('shutdown').id == 6
    assert [t.label for t in sm.available_transitions()] == ['cleanup', 'activate', 'shutdown']
    with pytest.raises(InvalidTransitionError, match="no transition 'deactivate' from state"):
        sm.transition_by_label('deactivate')
    with pytest.raises(InvalidTransitionError, match='no transition with id 5'):
        sm.transition_by_id(5)
    with pytest.raises(InvalidTransitionError):
        sm.take(TRANSITIONS[0])  # configure starts from unconfigured
