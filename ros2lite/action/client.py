"""ActionClient and ClientGoalHandle, shaped like rclpy.action.client.

The client is three service clients (send_goal, cancel_goal, get_result) and two
subscriptions (feedback, status) of its node. Feedback reaches the callback given for its
goal; the status topic keeps every live goal handle's `status` current.
"""

from __future__ import annotations

import threading
import time
import weakref
from collections.abc import Callable
from typing import TYPE_CHECKING, Generic, Protocol, cast

from ros2lite.action.entity import ActionEntity, GoalHandle
from ros2lite.action.goals import (
    TERMINAL_STATES,
    CancelGoal,
    GoalStatus,
    goal_key,
    new_goal_id,
)
from ros2lite.action.server import await_or_execute
from ros2lite.qos import QoSProfile, qos_profile_action_status_default, qos_profile_services_default
from ros2lite.task import Future
from ros2lite.type_support import FeedbackT, GoalT, ResultT
from ros2lite.waitable import NumberOfEntities

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.interfaces import Message
    from ros2lite.msgs.action_msgs.msg import GoalStatusArray
    from ros2lite.msgs.action_msgs.srv import CancelGoal_Response
    from ros2lite.msgs.builtin_interfaces.msg import Time
    from ros2lite.msgs.unique_identifier_msgs.msg import UUID
    from ros2lite.node import Node
    from ros2lite.service_introspection import IntrospectionMixin
    from ros2lite.type_support import Action, FeedbackMessage, GetResultResponse

# how often wait_for_server looks at the graph
_POLL = 0.05


class _SendGoalResponse(Protocol):
    """What the client reads of an `<A>_SendGoal_Response`."""

    accepted: bool
    stamp: Time


FeedbackCallback = Callable[['FeedbackMessage[FeedbackT]'], object]
"""Gets each `<A>_FeedbackMessage` (goal id and feedback) of one goal; may be `async def`."""


def _require_accepted(goal_handle: ClientGoalHandle[GoalT, ResultT, FeedbackT]) -> None:
    """Only an accepted goal can be canceled or have a result (rclpy's TypeError)."""
    if not goal_handle.accepted:
        raise TypeError('Action goal was not accepted')


class ClientGoalHandle(GoalHandle, Generic[GoalT, ResultT, FeedbackT]):
    """A goal as its client sees it: accepted or not, its status, and ways to end it."""

    def __init__(
        self,
        action_client: ActionClient[GoalT, ResultT, FeedbackT],
        goal_id: UUID,
        goal_response: Message,
    ) -> None:
        super().__init__(goal_id)
        self._action_client = action_client
        self._goal_response = cast(_SendGoalResponse, goal_response)
        self._status = GoalStatus.STATUS_UNKNOWN

    def __repr__(self) -> str:
        return (
            f'ClientGoalHandle <id: {list(self._key)}, '
            f'accepted: {self.accepted}, status: {self.status}>'
        )

    @property
    def stamp(self) -> Time:
        """When the server accepted (or rejected) the goal."""
        return self._goal_response.stamp

    @property
    def accepted(self) -> bool:
        """Whether the server accepted the goal."""
        return bool(self._goal_response.accepted)

    @property
    def status(self) -> int:
        """The goal's last known action_msgs/GoalStatus value."""
        return self._status

    def cancel_goal(self) -> CancelGoal_Response:
        """Ask the server to cancel; blocks until it answers (CancelGoal.Response)."""
        return self._action_client.cancel_goal(self)

    def cancel_goal_async(self) -> Future[CancelGoal_Response]:
        """Ask the server to cancel; the future gives its CancelGoal.Response."""
        return self._action_client.cancel_goal_async(self)

    def get_result(self) -> GetResultResponse[ResultT]:
        """Block until the goal ends; gives its GetResult response (status and result)."""
        return self._action_client.get_result(self)

    def get_result_async(self) -> Future[GetResultResponse[ResultT]]:
        """The future of the goal's GetResult response (status and result)."""
        return self._action_client.get_result_async(self)


class ActionClient(ActionEntity[GoalT, ResultT, FeedbackT]):
    """Sends goals to one action (rclpy.action.ActionClient's arguments and defaults)."""

    def __init__(
        self,
        node: Node,
        action_type: type[Action[GoalT, ResultT, FeedbackT]] | str,
        action_name: str,
        *,
        callback_group: CallbackGroup | None = None,
        goal_service_qos_profile: QoSProfile = qos_profile_services_default,
        result_service_qos_profile: QoSProfile = qos_profile_services_default,
        cancel_service_qos_profile: QoSProfile = qos_profile_services_default,
        feedback_sub_qos_profile: QoSProfile = QoSProfile(depth=10),  # noqa: B008
        status_sub_qos_profile: QoSProfile = qos_profile_action_status_default,
        fail_without_server: bool = False,
    ) -> None:
        """rclpy's arguments; `fail_without_server=True` (a ros2lite extra, for tools) ends a
        request the server never answers in an error instead of leaving it pending."""
        super().__init__(node, action_type, action_name, callback_group)
        self._lock = threading.Lock()
        self._feedback_callbacks: dict[bytes, FeedbackCallback[FeedbackT]] = {}
        self._goal_handles: dict[
            bytes, weakref.ref[ClientGoalHandle[GoalT, ResultT, FeedbackT]]
        ] = {}
        # goals sent but not answered yet, with the last status seen for them: the server
        # may publish a goal's status before its answer to send_goal arrives here
        self._unanswered: dict[bytes, int] = {}
        group = self.callback_group
        impl = self._action_type.Impl
        names = self._names
        self._goal_client, self._cancel_client, self._result_client = (
            node.create_client(
                srv_type,
                name,
                qos_profile=qos,
                callback_group=group,
                fail_without_server=fail_without_server,
            )
            for srv_type, name, qos in (
                (impl.SendGoalService, names.send_goal, goal_service_qos_profile),
                (impl.CancelGoalService, names.cancel_goal, cancel_service_qos_profile),
                (impl.GetResultService, names.get_result, result_service_qos_profile),
            )
        )
        self._feedback_sub = node.create_subscription(
            impl.FeedbackMessage,
            names.feedback,
            self._on_feedback,
            feedback_sub_qos_profile,
            callback_group=group,
        )
        self._status_sub = node.create_subscription(
            impl.GoalStatusMessage,
            names.status,
            self._on_status,
            status_sub_qos_profile,
            callback_group=group,
        )
        node.add_waitable(self)

    def get_num_entities(self) -> NumberOfEntities:
        """What rcl_action counts: the feedback and status subscriptions, three clients."""
        return NumberOfEntities(num_subscriptions=2, num_clients=3)

    # -- incoming ----------------------------------------------------------------------------
    async def _on_feedback(self, message: Message) -> None:
        # a coroutine, so that feedback callbacks may be `async def` too (as in rclpy)
        feedback = cast('FeedbackMessage[FeedbackT]', message)
        with self._lock:
            callback = self._feedback_callbacks.get(goal_key(feedback.goal_id))
        if callback is not None:
            await await_or_execute(callback, feedback)

    def _on_status(self, message: Message) -> None:
        with self._lock:
            for status in cast('GoalStatusArray', message).status_list:
                key = goal_key(status.goal_info.goal_id)
                if key in self._unanswered:
                    self._unanswered[key] = status.status
                    continue
                ref = self._goal_handles.get(key)
                handle = ref() if ref is not None else None
                if handle is None:
                    self._goal_handles.pop(key, None)
                    continue
                handle._status = status.status
                if status.status in TERMINAL_STATES:
                    del self._goal_handles[key]

    # -- goals -------------------------------------------------------------------------------
    def send_goal_async(
        self,
        goal: GoalT,
        feedback_callback: FeedbackCallback[FeedbackT] | None = None,
        goal_uuid: UUID | None = None,
    ) -> Future[ClientGoalHandle[GoalT, ResultT, FeedbackT]]:
        """Send a goal; the future gives its ClientGoalHandle once the server answers.

        `feedback_callback(feedback_message)` gets this goal's `<A>_FeedbackMessage`s."""
        if not isinstance(goal, self._action_type.Goal):
            raise TypeError(
                f'goal must be a {self._action_type.Goal.__name__}, got {type(goal).__name__}'
            )
        goal_id = new_goal_id() if goal_uuid is None else goal_uuid
        request = self._action_type.Impl.SendGoalService.Request(goal_id=goal_id, goal=goal)
        key = goal_key(goal_id)
        with self._lock:
            if feedback_callback is not None:
                self._feedback_callbacks[key] = feedback_callback
            self._unanswered[key] = GoalStatus.STATUS_UNKNOWN
        future: Future[ClientGoalHandle[GoalT, ResultT, FeedbackT]] = Future()
        try:
            call = self._goal_client.call_async(request)
        except BaseException:
            self._forget_goal(key)
            raise

        def answered(call_future: Future[Message]) -> None:
            exc = call_future.exception() if not call_future.cancelled() else None
            if call_future.cancelled() or exc is not None:
                self._forget_goal(key)
                if exc is not None:
                    future.set_exception(exc)
                else:
                    future.cancel()
                return
            handle = ClientGoalHandle(self, goal_id, cast('Message', call_future.result()))
            with self._lock:
                early = self._unanswered.pop(key, GoalStatus.STATUS_UNKNOWN)
                if handle.accepted:
                    handle._status = early
                    if early not in TERMINAL_STATES:
                        self._goal_handles[key] = weakref.ref(handle)
            if not handle.accepted:
                self._drop_feedback(key)
            future.set_result(handle)

        call.add_done_callback_now(answered)
        return future

    def send_goal(
        self,
        goal: GoalT,
        feedback_callback: FeedbackCallback[FeedbackT] | None = None,
        goal_uuid: UUID | None = None,
    ) -> GetResultResponse[ResultT] | None:
        """Send a goal and block until its GetResult response (None if it was rejected).

        The replies wake this thread directly, so no executor is needed for that; feedback
        callbacks still run only where the node is spun."""
        if not isinstance(goal, self._action_type.Goal):
            raise TypeError(
                f'goal must be a {self._action_type.Goal.__name__}, got {type(goal).__name__}'
            )
        goal_id = new_goal_id() if goal_uuid is None else goal_uuid
        key = goal_key(goal_id)
        with self._lock:
            if feedback_callback is not None:
                self._feedback_callbacks[key] = feedback_callback
            self._unanswered[key] = GoalStatus.STATUS_UNKNOWN
        try:
            response = self._goal_client.call(
                self._action_type.Impl.SendGoalService.Request(goal_id=goal_id, goal=goal)
            )
            handle = ClientGoalHandle(self, goal_id, response)
            if not handle.accepted:
                return None
            with self._lock:
                handle._status = self._unanswered.pop(key, GoalStatus.STATUS_UNKNOWN)
                self._goal_handles[key] = weakref.ref(handle)
            return self.get_result(handle)
        finally:
            self._forget_goal(key)

    def _drop_feedback(self, key: bytes) -> None:
        with self._lock:
            self._feedback_callbacks.pop(key, None)

    def _forget_goal(self, key: bytes) -> None:
        with self._lock:
            self._feedback_callbacks.pop(key, None)
            self._unanswered.pop(key, None)

    @staticmethod
    def _cancel_request(goal_handle: ClientGoalHandle[GoalT, ResultT, FeedbackT]) -> Message:
        """The CancelGoal request for an accepted goal (TypeError for one not accepted)."""
        _require_accepted(goal_handle)
        request = CancelGoal.Request()
        request.goal_info.goal_id = goal_handle.goal_id
        return request

    def _result_request(self, goal_handle: ClientGoalHandle[GoalT, ResultT, FeedbackT]) -> Message:
        """The GetResult request for an accepted goal (TypeError for one not accepted)."""
        _require_accepted(goal_handle)
        return self._action_type.Impl.GetResultService.Request(goal_id=goal_handle.goal_id)

    def cancel_goal_async(
        self, goal_handle: ClientGoalHandle[GoalT, ResultT, FeedbackT]
    ) -> Future[CancelGoal_Response]:
        """Ask the server to cancel the goal (ClientGoalHandle.cancel_goal_async)."""
        if not isinstance(goal_handle, ClientGoalHandle):
            raise TypeError('expected a ClientGoalHandle')
        request = self._cancel_request(goal_handle)
        return cast('Future[CancelGoal_Response]', self._cancel_client.call_async(request))

    def cancel_goal(
        self, goal_handle: ClientGoalHandle[GoalT, ResultT, FeedbackT]
    ) -> CancelGoal_Response:
        """Ask the server to cancel, blocking until it answers (ClientGoalHandle.cancel_goal)."""
        return cast(
            'CancelGoal_Response', self._cancel_client.call(self._cancel_request(goal_handle))
        )

    def get_result_async(
        self, goal_handle: ClientGoalHandle[GoalT, ResultT, FeedbackT]
    ) -> Future[GetResultResponse[ResultT]]:
        """The future of the goal's GetResult response (ClientGoalHandle.get_result_async)."""
        if not isinstance(goal_handle, ClientGoalHandle):
            raise TypeError('expected a ClientGoalHandle')
        key = goal_key(goal_handle.goal_id)
        request = self._result_request(goal_handle)
        future = cast('Future[GetResultResponse[ResultT]]', self._result_client.call_async(request))

        def done(f: Future[GetResultResponse[ResultT]]) -> None:
            self._drop_feedback(key)
            response = f.result() if not f.cancelled() and f.exception() is None else None
            if response is not None and response.status in TERMINAL_STATES:
                goal_handle._status = response.status

        future.add_done_callback_now(done)
        return future

    def get_result(
        self, goal_handle: ClientGoalHandle[GoalT, ResultT, FeedbackT]
    ) -> GetResultResponse[ResultT]:
        """Block until the goal ends; its GetResult response (ClientGoalHandle.get_result)."""
        response = cast(
            'GetResultResponse[ResultT]',
            self._result_client.call(self._result_request(goal_handle)),
        )
        self._drop_feedback(goal_key(goal_handle.goal_id))
        if response.status in TERMINAL_STATES:
            goal_handle._status = response.status
        return response

    # -- server discovery --------------------------------------------------------------------
    def server_is_ready(self) -> bool:
        """All three services answer and the feedback and status topics have a publisher
        (what rcl_action_server_is_available checks)."""
        return (
            self._goal_client.service_is_ready()
            and self._cancel_client.service_is_ready()
            and self._result_client.service_is_ready()
            and self._feedback_sub.get_publisher_count() > 0
            and self._status_sub.get_publisher_count() > 0
        )

    def wait_for_server(self, timeout_sec: float | None = None) -> bool:
        """Wait until the server is ready; False on timeout (None: wait forever)."""
        deadline = None if timeout_sec is None else time.monotonic() + timeout_sec
        while self._node.context.ok() and not self.server_is_ready():
            if deadline is not None and time.monotonic() >= deadline:
                break
            time.sleep(_POLL)
        return self.server_is_ready()

    def _introspected(self) -> tuple[IntrospectionMixin, ...]:
        """The action's three service clients, whose events its introspection reports."""
        return (self._goal_client, self._cancel_client, self._result_client)

    def _destroy_entities(self) -> None:
        """The three service clients and the feedback and status subscriptions."""
        node = self._node
        for client in (self._goal_client, self._cancel_client, self._result_client):
            node.destroy_client(client)
        node.destroy_subscription(self._feedback_sub)
        node.destroy_subscription(self._status_sub)
