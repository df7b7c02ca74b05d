"""`action send_goal`: send one goal, print its acceptance, feedback and result.

Ctrl-C while the goal is active cancels it first ("Canceling goal...", "Goal canceled."),
then leaves with status 2, as ros2cli does.
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING, TypeVar

import click

from .. import completion, numbers, render
from ..common import (
    connect,
    json_object,
    known_type_if_graph,
    message_fields,
    wait_saying_other_types,
)
from ..errors import CliError
from ..options import NDJSON, check_stdin, json_option, values_argument
from ..parsing import command

if TYPE_CHECKING:
    from ros2lite.action import ClientGoalHandle
    from ros2lite.interfaces import ActionType, Message
    from ros2lite.task import Future
    from ros2lite.tools.connection import Connection
    from ros2lite.type_support import FeedbackMessage

_T = TypeVar('_T')


def action_class(action_type: str) -> tuple[str, type[ActionType]]:
    """('pkg/action/Name', class) for 'pkg/action/Name' or 'pkg/Name'; a type no local
    package defines is fetched from a node that serves or uses it (one line on stderr)."""
    from ros2lite.action.goals import resolve_action_type
    from ros2lite.interfaces import InterfaceError

    def resolve() -> type[ActionType]:
        try:
            return resolve_action_type(action_type)
        except (InterfaceError, ValueError, TypeError, LookupError):
            raise CliError('The passed action type is invalid') from None

    try:
        cls = resolve()
    except CliError:
        parts = action_type.split('/')
        known_type_if_graph('/'.join([parts[0], 'action', parts[1]] if len(parts) == 2 else parts))
        cls = resolve()
    return cls._TYPE_NAME, cls


def build_goal(cls: type[ActionType], values: str) -> Message:
    from ros2lite.interfaces import set_message_fields

    goal = cls.Goal()
    try:
        obj = json_object(values)
        set_message_fields(goal, values if obj is None else message_fields(type(goal), obj))
    except Exception as e:  # any reason the values do not fit, in one line
        raise CliError(f'Failed to populate message fields: {e}') from None
    return goal


class FeedbackPrinter:
    """Prints feedback as ros2cli does, but never before the goal's acceptance line: the
    first feedback may overtake the server's answer to send_goal on the way here."""

    def __init__(self, as_json: bool = False) -> None:
        self._held: list[FeedbackMessage[Message]] | None = []
        self.as_json = as_json

    def __call__(self, message: FeedbackMessage[Message]) -> None:
        if self._held is not None:
            self._held.append(message)
        else:
            self._print(message)

    def release(self) -> None:
        held, self._held = self._held or [], None
        for message in held:
            self._print(message)

    def _print(self, message: FeedbackMessage[Message]) -> None:
        from ros2lite.interfaces import message_to_yaml

        if self.as_json:
            from ros2lite.interfaces.json_form import message_to_json

            render.print_json_line({'feedback': message_to_json(message.feedback)})
            return
        click.echo(f'Feedback:\n    {message_to_yaml(message.feedback)}')


@command('send_goal')
@click.argument('action_name', shell_complete=completion.actions)
@click.argument('action_type', shell_complete=completion.action_types)
@values_argument('goal', 'the goal')
@click.option('-f', '--feedback', is_flag=True, help='Echo feedback messages for the goal')
@click.option(
    '--timeout',
    type=numbers.seconds(),
    metavar='SECONDS',
    help='Give up when no action server shows up within this time (default: wait forever)',
)
@json_option(
    f'{NDJSON}: {{"goal", "accepted", "goal_id"}}, {{"feedback"}} each, {{"result", "status"}}'
)
def cli(
    action_name: str,
    action_type: str,
    goal: str | None,
    use_stdin: bool,
    feedback: bool,
    timeout: float | None,
    as_json: bool,
) -> None:
    """Send an action goal.

    GOAL fills the goal message in YAML (e.g. '{order: 5}') or JSON (as --json prints it).
    """
    check_stdin(goal, use_stdin, 'goal')
    values = sys.stdin.read() if use_stdin else (goal if goal is not None else '{}')
    type_name, cls = action_class(action_type)
    goal_msg = build_goal(cls, values)
    pkg, _, name = type_name.split('/')
    with connect() as conn:
        conn.node(f'_ros2lite_send_goal_{pkg}_action_{name}')
        send_goal(
            conn,
            cls,
            action_name,
            goal_msg,
            FeedbackPrinter(as_json) if feedback else None,
            timeout,
            as_json,
        )


def send_goal(
    conn: Connection,
    cls: type[ActionType],
    action_name: str,
    goal: Message,
    feedback: FeedbackPrinter | None,
    timeout: float | None,
    as_json: bool = False,
) -> None:
    from ros2lite.action import ActionClient
    from ros2lite.action.goals import GoalStatus, goal_id_hex, status_name
    from ros2lite.interfaces import message_to_yaml
    from ros2lite.interfaces.json_form import message_to_json

    try:
        # a server that vanishes mid-goal is reported, not waited for forever
        client = ActionClient(conn.node(), cls, action_name, fail_without_server=True)
    except ValueError as e:  # an invalid action name
        raise CliError(str(e)) from None
    from ros2lite.action.graph import get_action_names_and_types

    # with --json, stdout holds the objects alone; what happens meanwhile goes to stderr
    click.echo('Waiting for an action server to become available...', err=as_json)
    node = conn.node()
    if not wait_saying_other_types(
        lambda step: client.wait_for_server(timeout_sec=step),
        timeout,
        'action',
        client.action_name,
        cls._TYPE_NAME,
        lambda: get_action_names_and_types(node),
    ):
        raise CliError(f"No action server for '{client.action_name}' after {timeout} s")
    if not as_json:
        click.echo(f'Sending goal:\n     {message_to_yaml(goal)}')
    goal_handle = None
    try:
        goal_future = client.send_goal_async(goal, feedback)
        goal_handle = _outcome(conn, goal_future, 'sending goal')
        if as_json:
            render.print_json_line(
                {
                    'goal': message_to_json(goal),
                    'accepted': goal_handle.accepted,
                    'goal_id': goal_id_hex(goal_handle.goal_id) if goal_handle.accepted else None,
                }
            )
            if not goal_handle.accepted:
                return
        elif not goal_handle.accepted:
            click.echo('Goal was rejected.')
            return
        else:
            click.echo(f'Goal accepted with ID: {goal_id_hex(goal_handle.goal_id)}\n')
        if feedback is not None:
            feedback.release()
        result_future = goal_handle.get_result_async()
        result = _outcome(conn, result_future, 'getting result')
        if as_json:
            render.print_json_line(
                {'result': message_to_json(result.result), 'status': status_name(result.status)}
            )
            return
        click.echo(f'Result:\n    {message_to_yaml(result.result)}')
        click.echo(f'Goal finished with status: {status_name(result.status)}')
    except BaseException as e:
        # Ctrl-C (or SIGTERM) while the goal is active cancels it, as ros2cli does; a goal
        # whose first status has not arrived yet is just as alive. A failure such as the
        # server going away is reported as it is, with no cancel that could not succeed.
        if (
            not isinstance(e, Exception)
            and goal_handle is not None
            and goal_handle.status
            in (GoalStatus.STATUS_UNKNOWN, GoalStatus.STATUS_ACCEPTED, GoalStatus.STATUS_EXECUTING)
        ):
            _cancel(conn, goal_handle, as_json)
        raise
    finally:
        client.destroy()


def _outcome(conn: Connection, future: Future[_T], doing: str) -> _T:
    """Spin until `future` is done; its result, or ros2cli's error naming what failed."""
    conn.spin_until_future_complete(future)
    if future.cancelled() or future.exception() is not None:
        raise CliError(f'Exception while {doing}: {future.exception()!r}')
    result = future.result()
    if result is None:  # (goal handles and responses are never None)
        raise CliError(f'Exception while {doing}: no result')
    return result


def _cancel(
    conn: Connection,
    goal_handle: ClientGoalHandle[Message, Message, Message],
    as_json: bool = False,
) -> None:
    from ros2lite.action.goals import goal_key

    click.echo('Canceling goal...', err=as_json)
    response = _outcome(conn, goal_handle.cancel_goal_async(), 'canceling goal')
    canceling = response.goals_canceling
    if not canceling:
        raise CliError('Failed to cancel goal')
    if len(canceling) > 1:
        raise CliError('More than one goal canceled')
    if goal_key(canceling[0].goal_id) != goal_key(goal_handle.goal_id):
        raise CliError('Canceled goal with incorrect goal ID')
    click.echo('Goal canceled.', err=as_json)
