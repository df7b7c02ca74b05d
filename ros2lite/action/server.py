"""ActionServer and ServerGoalHandle, shaped like rclpy.action.server.

An action server is five ordinary entities of its node (rcl_action over rmw_zenoh has nothing
more): the send_goal, cancel_goal and get_result services, and the feedback and status
publishers. Requests run in the server's callback group; each accepted goal's execute
callback runs as a task on the node's executor, as in rclpy, so it may be `async def`.
get_result requests for goals still running are answered when the goal ends (deferred
service replies).
"""

from __future__ import annotations

import enum
import inspect
import threading
import traceback
from collections.abc import Awaitable, Callable
from typing import TYPE_CHECKING, Generic, Protocol, TypeVar, cast

from ros2lite.action.entity import ActionEntity, GoalHandle
from ros2lite.action.goals import (
    TERMINAL_STATES,
    CancelGoal,
    GoalEvent,
    GoalInfo,
    GoalStatus,
    GoalTable,
    goal_key,
)
from ros2lite.clock import Clock, ClockType
from ros2lite.qos import QoSProfile, qos_profile_action_status_default, qos_profile_services_default
from ros2lite.task import Future
from ros2lite.type_support import FeedbackT, GoalT, ResultT
from ros2lite.waitable import NumberOfEntities

if TYPE_CHECKING:
    from ros2lite.callback_groups import CallbackGroup
    from ros2lite.interfaces import Message
    from ros2lite.msgs.action_msgs.msg import GoalInfo as GoalInfoMsg
    from ros2lite.msgs.action_msgs.srv import CancelGoal_Request
    from ros2lite.msgs.unique_identifier_msgs.msg import UUID
    from ros2lite.node import Node
    from ros2lite.service import RequestHeader
    from ros2lite.service_introspection import IntrospectionMixin
    from ros2lite.type_support import Action

_T = TypeVar('_T')


class GoalResponse(enum.Enum):
    """What a goal callback answers."""

    REJECT = 1
    ACCEPT = 2


class CancelResponse(enum.Enum):
    """What a cancel callback answers."""

    REJECT = 1
    ACCEPT = 2


class _SendGoalRequest(Protocol):
    """What the server reads of an `<A>_SendGoal_Request`."""

    goal_id: UUID
    goal: Message


class _GoalIdRequest(Protocol):
    """What the server reads of an `<A>_GetResult_Request`."""

    goal_id: UUID


def default_goal_callback(goal_request: object) -> GoalResponse:
    """Accept every goal (rclpy's default)."""
    return GoalResponse.ACCEPT


def default_handle_accepted_callback(
    goal_handle: ServerGoalHandle[GoalT, ResultT, FeedbackT],
) -> None:
    """Start executing an accepted goal at once (rclpy's default)."""
    goal_handle.execute()


def default_cancel_callback(cancel_request: object) -> CancelResponse:
    """Refuse every cancel request (rclpy's default)."""
    return CancelResponse.REJECT


async def await_or_execute(callback: Callable[..., _T | Awaitable[_T]], *args: object) -> _T:
    """Call a plain or `async def` callback and give its result."""
    result = callback(*args)
    if inspect.isawaitable(result):
        return cast(_T, await result)
    return cast(_T, result)


class ServerGoalHandle(GoalHandle, Generic[GoalT, ResultT, FeedbackT]):
    """One accepted goal as the user's callbacks see it."""

    def __init__(
        self,
        action_server: ActionServer[GoalT, ResultT, FeedbackT],
        goal_info: GoalInfoMsg,
        goal_request: GoalT,
    ) -> None:
        super().__init__(goal_info.goal_id)
        self._action_server = action_server
        self._goal_info = goal_info
        self._goal_request = goal_request
        self._destroyed = False

    def __repr__(self) -> str:
        return f'ServerGoalHandle <id: {self._key.hex()}, status: {self.status}>'

    @property
    def request(self) -> GoalT:
        """The goal the client sent."""
        return self._goal_request

    @property
    def status(self) -> int:
        """The goal's action_msgs/GoalStatus value now."""
        return self._action_server.goal_status(self._key)

    @property
    def is_active(self) -> bool:
        """Whether the goal is accepted, executing or canceling (not ended)."""
        return self.status in (
            GoalStatus.STATUS_ACCEPTED,
            GoalStatus.STATUS_EXECUTING,
            GoalStatus.STATUS_CANCELING,
        )

    @property
    def is_cancel_requested(self) -> bool:
        """True once a cancel was accepted, and also once the server is gone (destroyed or
        shut down), so that execute loops written for cancellation end there too."""
        return self._destroyed or self.status == GoalStatus.STATUS_CANCELING

    def execute(
        self, execute_callback: ExecuteCallback[GoalT, ResultT, FeedbackT] | None = None
    ) -> None:
        """Start executing (with the server's execute callback unless one is given).

        A goal whose cancel was requested before it started keeps CANCELING: the callback
        still runs, so that it can finish the goal as canceled."""
        if not self.is_cancel_requested:
            self._update_state(GoalEvent.EXECUTE)
        self._action_server.notify_execute(self, execute_callback)

    def publish_feedback(self, feedback: FeedbackT) -> None:
        """Send feedback to the client(s) on the action's feedback topic."""
        server = self._action_server
        # the class's Feedback (the Action protocol types it as an instance's property)
        feedback_type = cast('type[FeedbackT]', server.action_type.Feedback)
        if not isinstance(feedback, feedback_type):
            raise TypeError(
                f'feedback must be a {feedback_type.__name__}, got {type(feedback).__name__}'
            )
        if not self._destroyed:
            server.publish_feedback(self._goal_info.goal_id, feedback)

    def succeed(self) -> None:
        """Mark the goal succeeded (the execute callback's result is sent)."""
        self._update_state(GoalEvent.SUCCEED)

    def abort(self) -> None:
        """Mark the goal aborted."""
        self._update_state(GoalEvent.ABORT)

    def canceled(self) -> None:
        """Mark a canceling goal canceled."""
        self._update_state(GoalEvent.CANCELED)

    def destroy(self) -> None:
        """Detach from the server: state changes and feedback are ignored from now on."""
        self._destroyed = True

    def _update_state(self, event: GoalEvent) -> None:
        if not self._destroyed:
            self._action_server.update_goal(self._key, event)


ExecuteCallback = Callable[
    [ServerGoalHandle[GoalT, ResultT, FeedbackT]], ResultT | Awaitable[ResultT]
]
"""Runs an accepted goal and returns its result (may be `async def`)."""
GoalCallback = Callable[[GoalT], GoalResponse | Awaitable[GoalResponse]]
"""Accepts or rejects a goal request."""
HandleAcceptedCallback = Callable[[ServerGoalHandle[GoalT, ResultT, FeedbackT]], object]
"""Told of each accepted goal; calls `goal_handle.execute()` now or later."""
CancelCallback = Callable[
    [ServerGoalHandle[GoalT, ResultT, FeedbackT]], CancelResponse | Awaitable[CancelResponse]
]
"""Accepts or rejects a request to cancel a goal."""


class ActionServer(ActionEntity[GoalT, ResultT, FeedbackT]):
    """Serves one action on a node (rclpy.action.ActionServer's arguments and defaults)."""

    def __init__(
        self,
        node: Node,
        action_type: type[Action[GoalT, ResultT, FeedbackT]] | str,
        action_name: str,
        execute_callback: ExecuteCallback[GoalT, ResultT, FeedbackT],
        *,
        callback_group: CallbackGroup | None = None,
        goal_callback: GoalCallback[GoalT] = default_goal_callback,
        handle_accepted_callback: HandleAcceptedCallback[
            GoalT, ResultT, FeedbackT
        ] = default_handle_accepted_callback,
        cancel_callback: CancelCallback[GoalT, ResultT, FeedbackT] = default_cancel_callback,
        goal_service_qos_profile: QoSProfile = qos_profile_services_default,
        result_service_qos_profile: QoSProfile = qos_profile_services_default,
        cancel_service_qos_profile: QoSProfile = qos_profile_services_default,
        feedback_pub_qos_profile: QoSProfile = QoSProfile(depth=10),  # noqa: B008
        status_pub_qos_profile: QoSProfile = qos_profile_action_status_default,
        result_timeout: float = 900,
    ) -> None:
        super().__init__(node, action_type, action_name, callback_group)
        self._logger = node.get_logger()
        self._lock = threading.RLock()
        self._goals = GoalTable(result_timeout)
        self._goal_handles: dict[bytes, ServerGoalHandle[GoalT, ResultT, FeedbackT]] = {}
        self._result_futures: dict[bytes, Future[Message]] = {}
        self.register_execute_callback(execute_callback)
        self.register_goal_callback(goal_callback)
        self.register_handle_accepted_callback(handle_accepted_callback)
        self.register_cancel_callback(cancel_callback)
        group = self.callback_group
        impl = self._action_type.Impl
        names = self._names
        # rcl_action's order: the three services, then feedback and status publishers
        self._goal_service, self._cancel_service, self._result_service = (
            node.create_service(
                srv_type, name, handler, qos_profile=qos, callback_group=group, deferred=True
            )
            for srv_type, name, handler, qos in (
                (
                    impl.SendGoalService,
                    names.send_goal,
                    self._execute_goal_request,
                    goal_service_qos_profile,
                ),
                (
                    impl.CancelGoalService,
                    names.cancel_goal,
                    self._execute_cancel_request,
                    cancel_service_qos_profile,
                ),
                (
                    impl.GetResultService,
                    names.get_result,
                    self._on_result_request,
                    result_service_qos_profile,
                ),
            )
        )
        self._feedback_pub = node.create_publisher(
            impl.FeedbackMessage, names.feedback, feedback_pub_qos_profile
        )
        self._status_pub = node.create_publisher(
            impl.GoalStatusMessage, names.status, status_pub_qos_profile
        )
        # as rcl_action's timer: finished goals are forgotten `result_timeout` after they
        # ended, whether or not anyone asks the server anything meanwhile

        self._expiry_timer = node.create_timer(
            max(result_timeout, 0.001),
            self._expire_goals,
            callback_group=group,
            clock=Clock(clock_type=ClockType.STEADY_TIME),
            autostart=False,
        )
        node.add_waitable(self)

    def get_num_entities(self) -> NumberOfEntities:
        """What rcl_action counts: three services and the expiry timer."""
        return NumberOfEntities(num_timers=1, num_services=3)

    def _expire_goals(self) -> None:
        """Timer: forget the goals whose results expired; wake again for the next one."""
        with self._lock:
            before = len(self._goals)
            self._goals.expire()
            self._forget_expired()
            expired = len(self._goals) < before
            left = self._goals.next_expiry()
        if expired:
            self._publish_status()
        self._plan_expiry(left)

    def _plan_expiry(self, left: float | None) -> None:
        timer = self._expiry_timer
        if left is None:
            timer.cancel()
        else:
            timer.timer_period_ns = max(int(left * 1e9), 1_000_000)
            timer.reset()

    def _introspected(self) -> tuple[IntrospectionMixin, ...]:
        """The action's three services, whose events its introspection reports."""
        return (self._goal_service, self._cancel_service, self._result_service)

    # -- rclpy's registration API ---------------------------------------------------------------
    def register_execute_callback(
        self, execute_callback: ExecuteCallback[GoalT, ResultT, FeedbackT]
    ) -> None:
        """Use `execute_callback` for goals executed from now on."""
        if not callable(execute_callback):
            raise TypeError('Failed to register execute callback: not callable')
        self._execute_callback = execute_callback

    def register_goal_callback(self, goal_callback: GoalCallback[GoalT] | None) -> None:
        """Use `goal_callback` (None: accept all) for goal requests from now on."""
        self._goal_callback: GoalCallback[GoalT] = goal_callback or default_goal_callback

    def register_handle_accepted_callback(
        self, handle_accepted_callback: HandleAcceptedCallback[GoalT, ResultT, FeedbackT] | None
    ) -> None:
        """Use `handle_accepted_callback` (None: execute at once) for accepted goals."""
        self._handle_accepted_callback: HandleAcceptedCallback[GoalT, ResultT, FeedbackT] = (
            handle_accepted_callback or default_handle_accepted_callback
        )

    def register_cancel_callback(
        self, cancel_callback: CancelCallback[GoalT, ResultT, FeedbackT] | None
    ) -> None:
        """Use `cancel_callback` (None: reject all) for cancel requests from now on."""
        self._cancel_callback: CancelCallback[GoalT, ResultT, FeedbackT] = (
            cancel_callback or default_cancel_callback
        )

    # -- requests (deferred service callbacks; coroutines, so user callbacks may be too) -----
    async def _execute_goal_request(self, message: Message, header: RequestHeader) -> None:
        request = cast(_SendGoalRequest, message)
        key = goal_key(request.goal_id)
        with self._lock:
            self._goals.expire()
            self._forget_expired()
            exists = key in self._goals
        accepted = False
        if exists:
            self._logger.error(f'Received a goal with an ID already in use: {key.hex()}')
        else:
            try:
                response = await await_or_execute(self._goal_callback, request.goal)
            except Exception as e:  # the client still gets an answer: rejected
                self._logger.error(f'Error raised in goal callback: {e!r}; rejecting goal')
                response = GoalResponse.REJECT
            if isinstance(response, GoalResponse):
                accepted = response == GoalResponse.ACCEPT
            else:
                self._logger.warning(
                    'Goal request callback did not return a GoalResponse type. Rejecting goal.'
                )
        info = GoalInfo(goal_id=request.goal_id)
        goal_handle = None
        if accepted:
            info.stamp = self._node.get_clock().now().to_msg()
            with self._lock:
                if key in self._goals:  # the same id accepted meanwhile
                    accepted = False
                else:
                    self._goals.add(info)
                    goal_handle = ServerGoalHandle(self, info, cast(GoalT, request.goal))
                    self._goal_handles[key] = goal_handle
                    self._result_futures[key] = Future()
        response_msg = self._action_type.Impl.SendGoalService.Response(
            accepted=accepted, stamp=info.stamp
        )
        self._goal_service.send_response(response_msg, header)
        if goal_handle is None:
            return
        self._publish_status()
        await await_or_execute(self._handle_accepted_callback, goal_handle)

    async def _execute_cancel_request(self, message: Message, header: RequestHeader) -> None:
        request = cast('CancelGoal_Request', message)
        with self._lock:
            code, infos = self._goals.select_cancel(request)
        canceling = []
        for info in infos:
            key = goal_key(info.goal_id)
            goal_handle = self._goal_handles.get(key)
            if goal_handle is None:
                continue
            try:
                answer = await await_or_execute(self._cancel_callback, goal_handle)
            except Exception as e:  # the client still gets an answer: not canceled
                self._logger.error(f'Error raised in cancel callback: {e!r}')
                answer = CancelResponse.REJECT
            if answer == CancelResponse.ACCEPT:
                try:
                    self.update_goal(key, GoalEvent.CANCEL_GOAL)
                except RuntimeError:
                    continue  # it ended while the callback ran
                canceling.append(info)
        if infos and not canceling:
            code = CancelGoal.Response.ERROR_REJECTED  # the user turned every goal down
        self._cancel_service.send_response(
            CancelGoal.Response(return_code=code, goals_canceling=canceling), header
        )

    def _on_result_request(self, message: Message, header: RequestHeader) -> None:
        key = goal_key(cast(_GoalIdRequest, message).goal_id)
        with self._lock:
            self._goals.expire()
            self._forget_expired()
            future = self._result_futures.get(key)
        if future is None:
            response = self._action_type.Impl.GetResultService.Response(
                status=GoalStatus.STATUS_UNKNOWN
            )
            self._result_service.send_response(response, header)
            return
        # answered now if the goal is over, or the moment it ends
        future.add_done_callback_now(lambda f: self._send_result(f.result(), header))

    def _send_result(self, response: Message | None, header: RequestHeader) -> None:
        if self._destroyed or response is None:
            # the service is gone, and with it the request (a result future is only ever
            # completed with a response, so None does not happen)
            return
        try:
            self._result_service.send_response(response, header)
        except Exception as e:  # e.g. the session closed meanwhile
            self._logger.debug(f'could not send a result: {e}')

    # -- goal bookkeeping (its goal handles ask through these) -------------------------------
    def goal_status(self, key: bytes) -> int:
        """The action_msgs/GoalStatus value of the goal `key` (UNKNOWN once forgotten)."""
        with self._lock:
            entry = self._goals.get(key)
            return GoalStatus.STATUS_UNKNOWN if entry is None else entry.state

    def update_goal(self, key: bytes, event: GoalEvent) -> None:
        """Move the goal `key` on by `event` and publish the statuses (RuntimeError for a
        transition its state does not allow; nothing for a goal already forgotten)."""
        with self._lock:
            if key not in self._goals:
                return  # expired already
            self._goals.update(key, event)
        self._publish_status()

    def _forget_expired(self) -> None:
        for key in [k for k in self._goal_handles if k not in self._goals]:
            self._goal_handles.pop(key).destroy()
            self._result_futures.pop(key, None)

    def _publish_status(self) -> None:
        if self._destroyed:
            return
        with self._lock:
            self._goals.expire()
            self._forget_expired()
            self._status_pub.publish(self._goals.status_array())

    def publish_feedback(self, goal_id: UUID, feedback: FeedbackT) -> None:
        """Send `feedback` for the goal `goal_id` on the action's feedback topic."""
        message = self._action_type.Impl.FeedbackMessage(goal_id=goal_id, feedback=feedback)
        self._feedback_pub.publish(message)

    def notify_execute(
        self,
        goal_handle: ServerGoalHandle[GoalT, ResultT, FeedbackT],
        execute_callback: ExecuteCallback[GoalT, ResultT, FeedbackT] | None,
    ) -> None:
        """Run the goal's execute callback (the server's unless one is given) as a task of
        the node's executor (rclpy's name)."""
        callback = execute_callback or self._execute_callback
        executor = self._node.executor
        if executor is None:
            raise RuntimeError(
                'the action server\'s node must be added to an executor to execute goals'
            )
        executor.create_task(self._execute_goal, callback, goal_handle)

    async def _execute_goal(
        self,
        execute_callback: ExecuteCallback[GoalT, ResultT, FeedbackT],
        goal_handle: ServerGoalHandle[GoalT, ResultT, FeedbackT],
    ) -> None:
        key = goal_key(goal_handle.goal_id)
        result_type = self._action_type.Result
        result: object
        try:
            result = await await_or_execute(execute_callback, goal_handle)
        except Exception as e:
            self._logger.error(f'Error raised in execute callback: {e}')
            traceback.print_exc()
            result = result_type()
        if not isinstance(result, result_type):
            self._logger.error(
                f'Execute callback returned {type(result).__name__}, not a '
                f'{result_type.__name__}; sending an empty result'
            )
            result = result_type()
        if goal_handle.is_active:
            self._logger.warning(f'Goal state not set, assuming aborted. Goal ID: {key.hex()}')
            goal_handle.abort()
        status = goal_handle.status
        if status not in TERMINAL_STATES:
            return  # expired or destroyed meanwhile: nobody can ask for the result
        response = self._action_type.Impl.GetResultService.Response(status=status, result=result)
        with self._lock:
            future = self._result_futures.get(key)
            self._goals.finish(key)
            left = self._goals.next_expiry()
        self._plan_expiry(left)
        if future is not None and not future.done():
            future.set_result(response)

    def _destroy_entities(self) -> None:
        """The three services, the feedback and status publishers, and the expiry timer."""
        node = self._node
        for service in (self._goal_service, self._cancel_service, self._result_service):
            node.destroy_service(service)
        node.destroy_publisher(self._feedback_pub)
        node.destroy_publisher(self._status_pub)
        node.destroy_timer(self._expiry_timer)
        with self._lock:
            for handle in self._goal_handles.values():
                handle.destroy()
            self._goal_handles.clear()
