"""The managed-node state machine of ROS 2 (design.ros2.org "node lifecycle"), as data.

States, transitions, their ids and labels are lifecycle_msgs' and rcl_lifecycle's default
state machine's, in rcl's registration order — `ros2 lifecycle list -a` prints them in this
order, and a C++ node answers `get_transition_graph` the same way. Pure logic: no messages,
no I/O; :mod:`ros2lite.lifecycle.node` drives it and serves it.
"""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import NamedTuple

from ros2lite.exceptions import Ros2liteError

__all__ = [
    'STATES',
    'TRANSITIONS',
    'InvalidTransitionError',
    'LifecycleState',
    'StateMachine',
    'TransitionCallbackReturn',
    'TransitionDef',
]


class InvalidTransitionError(Ros2liteError, RuntimeError):
    """The transition does not start from the current state (rclpy raises RCLError here)."""


class LifecycleState(NamedTuple):
    """A state as rclpy hands it to transition callbacks: (label, state_id)."""

    label: str
    state_id: int


# lifecycle_msgs/msg/State ids
UNKNOWN, UNCONFIGURED, INACTIVE, ACTIVE, FINALIZED = 0, 1, 2, 3, 4
CONFIGURING, CLEANINGUP, SHUTTINGDOWN, ACTIVATING, DEACTIVATING, ERRORPROCESSING = range(10, 16)

STATES: dict[int, str] = {
    UNKNOWN: 'unknown',
    UNCONFIGURED: 'unconfigured',
    INACTIVE: 'inactive',
    ACTIVE: 'active',
    FINALIZED: 'finalized',
    CONFIGURING: 'configuring',
    CLEANINGUP: 'cleaningup',
    SHUTTINGDOWN: 'shuttingdown',
    ACTIVATING: 'activating',
    DEACTIVATING: 'deactivating',
    ERRORPROCESSING: 'errorprocessing',
}
PRIMARY_STATES = (UNKNOWN, UNCONFIGURED, INACTIVE, ACTIVE, FINALIZED)


class TransitionCallbackReturn(enum.IntEnum):
    """What a transition callback answers (lifecycle_msgs/msg/Transition's callback ids)."""

    SUCCESS = 97
    FAILURE = 98
    ERROR = 99

    def to_label(self) -> str:
        """The label of the transition this answer takes out of a transition state."""
        return _RESULT_LABELS[self]


_RESULT_LABELS = {
    TransitionCallbackReturn.SUCCESS: 'transition_success',
    TransitionCallbackReturn.FAILURE: 'transition_failure',
    TransitionCallbackReturn.ERROR: 'transition_error',
}


@dataclass(frozen=True)
class TransitionDef:
    """One edge of the graph: lifecycle_msgs/msg/TransitionDescription as plain data."""

    id: int
    label: str
    start: int
    goal: int


def _result_edges(base: int, start: int, success: int, failure: int) -> list[TransitionDef]:
    """The three ways out of a transition state (success, failure, error)."""
    return [
        TransitionDef(base, 'transition_success', start, success),
        TransitionDef(base + 1, 'transition_failure', start, failure),
        TransitionDef(base + 2, 'transition_error', start, ERRORPROCESSING),
    ]


# rcl_lifecycle's default state machine, in its registration order
TRANSITIONS: tuple[TransitionDef, ...] = (
    TransitionDef(1, 'configure', UNCONFIGURED, CONFIGURING),
    *_result_edges(10, CONFIGURING, INACTIVE, UNCONFIGURED),
    TransitionDef(2, 'cleanup', INACTIVE, CLEANINGUP),
    *_result_edges(20, CLEANINGUP, UNCONFIGURED, INACTIVE),
    TransitionDef(3, 'activate', INACTIVE, ACTIVATING),
    *_result_edges(30, ACTIVATING, ACTIVE, INACTIVE),
    TransitionDef(4, 'deactivate', ACTIVE, DEACTIVATING),
    *_result_edges(40, DEACTIVATING, INACTIVE, ACTIVE),
    TransitionDef(5, 'shutdown', UNCONFIGURED, SHUTTINGDOWN),
    TransitionDef(6, 'shutdown', INACTIVE, SHUTTINGDOWN),
    TransitionDef(7, 'shutdown', ACTIVE, SHUTTINGDOWN),
    *_result_edges(50, SHUTTINGDOWN, FINALIZED, FINALIZED),
    TransitionDef(60, 'transition_success', ERRORPROCESSING, UNCONFIGURED),
    TransitionDef(61, 'transition_failure', ERRORPROCESSING, FINALIZED),
    TransitionDef(62, 'transition_error', ERRORPROCESSING, FINALIZED),
)


class StateMachine:
    """Where a managed node is, and which transitions lead on from there."""

    def __init__(self) -> None:
        self.current = UNCONFIGURED

    @property
    def current_state(self) -> tuple[int, str]:
        """(id, label) of the current state, as rclpy's state machine reports it."""
        return self.current, STATES[self.current]

    def available_transitions(self) -> list[TransitionDef]:
        """The transitions that start from the current state."""
        return [t for t in TRANSITIONS if t.start == self.current]

    def transition_by_id(self, transition_id: int) -> TransitionDef:
        """The transition `transition_id` out of the current state."""
        for t in self.available_transitions():
            if t.id == transition_id:
                return t
        raise InvalidTransitionError(
            f"no transition with id {transition_id} from state '{STATES[self.current]}'"
        )

    def transition_by_label(self, label: str) -> TransitionDef:
        """The transition called `label` out of the current state ('shutdown' is three
        transitions, one per primary state: the label picks the right one)."""
        for t in self.available_transitions():
            if t.label == label:
                return t
        raise InvalidTransitionError(f"no transition '{label}' from state '{STATES[self.current]}'")

    def take(self, transition: TransitionDef) -> None:
        """Follow `transition` (which must start here)."""
        if transition.start != self.current:
            raise InvalidTransitionError(
                f"transition '{transition.label}' [{transition.id}] does not start from "
                f"state '{STATES[self.current]}'"
            )
        self.current = transition.goal
