"""Event handlers: what to do when an event happens (entities to visit, or a function)."""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, TypeAlias, cast

from .entity import LaunchDescriptionEntity
from .events import (
    ActionLike,
    Event,
    ExecutionComplete,
    ProcessExited,
    ProcessIO,
    ProcessStarted,
    ProcessStderr,
    ProcessStdout,
    Shutdown,
)

if TYPE_CHECKING:
    from .context import LaunchContext

__all__ = [
    'EventHandler',
    'OnExecutionComplete',
    'OnProcessExit',
    'OnProcessIO',
    'OnProcessStart',
    'OnShutdown',
]


# what a handler visits: one entity, several, or none
SomeEntities: TypeAlias = 'LaunchDescriptionEntity | Sequence[LaunchDescriptionEntity] | None'
# entities, or a function of the event that returns them
Reaction: TypeAlias = 'SomeEntities | Callable[[Event, LaunchContext], SomeEntities]'
# the action an event must be about: one action, a predicate on the action, or any (None)
TargetAction: TypeAlias = 'ActionLike | Callable[[ActionLike | None], bool] | None'


def _as_list(entities: SomeEntities) -> list[LaunchDescriptionEntity] | None:
    if entities is None:
        return None
    if isinstance(entities, (list, tuple)):
        return list(entities)
    return [cast('LaunchDescriptionEntity', entities)]


class EventHandler:
    """Handles events that `matcher` accepts by returning `entities` to visit."""

    def __init__(
        self,
        *,
        matcher: Callable[[Event], bool],
        entities: SomeEntities = None,
        handle_once: bool = False,
    ) -> None:
        self.matcher = matcher
        self.entities = _as_list(entities)
        self.handle_once = handle_once
        self.captured_locals: dict[str, object] = {}

    def matches(self, event: Event) -> bool:
        """Whether this handler reacts to `event`."""
        return bool(self.matcher(event))

    def handle(self, event: Event, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        """The entities to visit for `event` (`context.locals.event` is set meanwhile)."""
        context.extend_locals({'event': event})
        if self.handle_once:
            context.unregister_event_handler(self)
        return self.entities

    def describe(self) -> str:
        """The handler's class name, for introspection."""
        return type(self).__name__

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        """The entities it visits when its event happens."""
        return list(self.entities or [])


def _target_matcher(target: TargetAction) -> Callable[[ActionLike | None], bool]:
    if target is None:
        return lambda _action: True
    if callable(target) and not hasattr(target, 'execute'):
        return lambda action: bool(target(action))
    return lambda action: action is target


class _OnActionEvent(EventHandler):
    """An event about an action (a process), optionally only for `target_action`; the
    reaction is entities or a function `(event, context) -> entities`."""

    event_type: type[Event] = Event

    def __init__(
        self,
        *,
        target_action: TargetAction = None,
        on_event: Reaction = None,
        handle_once: bool = False,
    ) -> None:
        is_target = _target_matcher(target_action)
        event_type = self.event_type

        def matcher(event: Event) -> bool:
            return isinstance(event, event_type) and is_target(getattr(event, 'action', None))

        self.target_action = target_action
        self.on_event = on_event
        super().__init__(
            matcher=matcher,
            entities=None if callable(on_event) else on_event,
            handle_once=handle_once,
        )

    def handle(self, event: Event, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        entities = super().handle(event, context)
        if callable(self.on_event):
            return _as_list(self.on_event(event, context))
        return entities


class OnProcessExit(_OnActionEvent):
    """When a process (the target, or any) exits."""

    event_type = ProcessExited

    def __init__(
        self,
        *,
        target_action: TargetAction = None,
        on_exit: Reaction = None,
        handle_once: bool = False,
    ) -> None:
        super().__init__(target_action=target_action, on_event=on_exit, handle_once=handle_once)


class OnProcessStart(_OnActionEvent):
    """When a process (the target, or any) has started."""

    event_type = ProcessStarted

    def __init__(
        self,
        *,
        target_action: TargetAction = None,
        on_start: Reaction = None,
        handle_once: bool = False,
    ) -> None:
        super().__init__(target_action=target_action, on_event=on_start, handle_once=handle_once)


class OnExecutionComplete(_OnActionEvent):
    """When an action has finished executing."""

    event_type = ExecutionComplete

    def __init__(
        self,
        *,
        target_action: TargetAction = None,
        on_completion: Reaction = None,
        handle_once: bool = False,
    ) -> None:
        super().__init__(
            target_action=target_action, on_event=on_completion, handle_once=handle_once
        )


class OnShutdown(EventHandler):
    """When the launch begins to shut down; `on_shutdown` is entities or a function."""

    def __init__(self, *, on_shutdown: Reaction, handle_once: bool = False) -> None:
        self.on_shutdown = on_shutdown
        super().__init__(
            matcher=lambda event: isinstance(event, Shutdown),
            entities=None if callable(on_shutdown) else on_shutdown,
            handle_once=handle_once,
        )

    def handle(self, event: Event, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        """The entities to visit at shutdown (a function's result, or the given ones)."""
        entities = super().handle(event, context)
        if callable(self.on_shutdown):
            return _as_list(self.on_shutdown(event, context))
        return entities


# what a line of output may trigger: entities to visit, or nothing
IOCallback = Callable[[ProcessIO], 'SomeEntities']


class OnProcessIO(EventHandler):
    """For each line a process writes: `on_stdout(event)` / `on_stderr(event)`."""

    def __init__(
        self,
        *,
        target_action: TargetAction = None,
        on_stdin: IOCallback | None = None,
        on_stdout: IOCallback | None = None,
        on_stderr: IOCallback | None = None,
    ) -> None:
        is_target = _target_matcher(target_action)
        self.target_action = target_action
        self.on_stdin = on_stdin
        self.on_stdout = on_stdout
        self.on_stderr = on_stderr
        super().__init__(
            matcher=lambda e: isinstance(e, ProcessIO) and is_target(getattr(e, 'action', None))
        )

    def handle(self, event: Event, context: LaunchContext) -> list[LaunchDescriptionEntity] | None:
        """What the stdout/stderr callback returns for this line."""
        super().handle(event, context)
        if isinstance(event, ProcessStdout) and self.on_stdout is not None:
            return _as_list(self.on_stdout(event))
        if isinstance(event, ProcessStderr) and self.on_stderr is not None:
            return _as_list(self.on_stderr(event))
        return None


def entities_of(handlers: Iterable[EventHandler]) -> list[LaunchDescriptionEntity]:
    """Every entity the handlers hold (for `launch -s`/`-p`)."""
    return [e for h in handlers for e in h.describe_sub_entities()]
