"""What an action client and an action server share, and what their goal handles share.

Both ends are a waitable of their node made of five entities that carry the action's names;
both goal handles are known by their goal's id. Written once here, so that the two ends
cannot drift apart on how they resolve names, join their node or leave the graph.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Generic, cast

from ros2lite.action.goals import ActionNames, goal_key, resolve_action_name, resolve_action_type
from ros2lite.runtime.executable import Executable
from ros2lite.service_introspection import Introspectable
from ros2lite.type_support import FeedbackT, GoalT, ResultT

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.msgs.unique_identifier_msgs.msg import UUID
    from ros2lite.node import Node
    from ros2lite.type_support import Action


class ActionEntity(Introspectable, Executable, Generic[GoalT, ResultT, FeedbackT]):
    """An action client or server: its node, its action's type and names, and its life in
    the node (a waitable whose own work is done by its services, clients and topics)."""

    _node: Node

    def __init__(
        self,
        node: Node,
        action_type: type[Action[GoalT, ResultT, FeedbackT]] | str,
        action_name: str,
        callback_group: CallbackGroup | None,
    ) -> None:
        self._action_type = resolve_action_type(action_type)
        self._action_name = action_name
        self._names = ActionNames(
            resolve_action_name(node, action_name), self._action_type._TYPE_NAME
        )
        self._destroyed = False
        # a waitable of the node, as in rclpy: destroy_node() destroys it too
        super().__init__(node, callback_group)

    def run_pending(self, batch: bool, stop: Callable[[], bool] | None) -> None:
        return None  # never has work of its own

    @property
    def action_type(self) -> type[Action[GoalT, ResultT, FeedbackT]]:
        """The action class."""
        return cast('type[Action[GoalT, ResultT, FeedbackT]]', self._action_type)

    @property
    def action_name(self) -> str:
        """The fully resolved action name."""
        return self._names.action

    def destroy(self) -> None:
        """Withdraw the five entities from the graph."""
        if self._destroyed:
            return
        self._destroyed = True
        self._node.remove_waitable(self)
        self._destroy_entities()

    def _destroy_entities(self) -> None:
        """Destroy the services or clients and the topics this end is made of."""
        raise NotImplementedError


class GoalHandle:
    """A goal handle of either end: equal to another of its kind with the same goal id."""

    def __init__(self, goal_id: UUID) -> None:
        self._goal_id = goal_id
        self._key = goal_key(goal_id)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, type(self)) and self._key == other._key

    def __hash__(self) -> int:
        return hash(self._key)

    @property
    def goal_id(self) -> UUID:
        """The goal's id."""
        return self._goal_id
