"""The actions that shape a launch's flow: groups and includes, timers, events and their
handlers, log lines and shutdown (the rest of the actions are in :mod:`.actions`)."""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from .actions import (
    Action,
    ActionOptions,
    LaunchDescription,
    LaunchDescriptionSource,
    PopLaunchConfigurations,
    PushLaunchConfigurations,
    SetLaunchConfiguration,
    declared_arguments,
    giving,
    include_chain,
    include_key,
    including,
    reading_from,
    seconds_of,
)
from .context import LaunchContext
from .entity import Entities, LaunchDescriptionEntity
from .errors import LaunchError
from .events import Event
from .events import Shutdown as ShutdownEvent
from .sources import AnyLaunchDescriptionSource
from .substitutions import (
    SomeSubstitutionsType,
    SubstitutionMapping,
    TextSubstitution,
    describe_substitutions,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from .event_handlers import EventHandler

__all__ = [
    'EmitEvent',
    'GroupAction',
    'IncludeLaunchDescription',
    'LogInfo',
    'RegisterEventHandler',
    'Shutdown',
    'TimerAction',
    'UnregisterEventHandler',
]


# -- structure -----------------------------------------------------------------------------------


class GroupAction(Action):
    """A list of actions under one condition; `scoped` (the default) keeps configurations,
    environment, namespace, parameters and remaps set inside from leaking out."""

    def __init__(
        self,
        actions: Iterable[LaunchDescriptionEntity],
        *,
        scoped: bool = True,
        forwarding: bool = True,
        launch_configurations: SubstitutionMapping | None = None,
        **kwargs: Unpack[ActionOptions],
    ) -> None:
        super().__init__(**kwargs)
        self.actions = list(actions)
        self.scoped = scoped
        self.forwarding = forwarding
        self.launch_configurations = dict(launch_configurations or {})

    def execute(self, context: LaunchContext) -> Entities | None:
        """Its actions, wrapped in a scope unless unscoped, after its launch configurations."""
        sets: Entities = [
            SetLaunchConfiguration(k, v) for k, v in self.launch_configurations.items()
        ]
        if not self.scoped:
            return [*sets, *self.actions]
        return [
            PushLaunchConfigurations(forwarding=self.forwarding),
            *sets,
            *self.actions,
            PopLaunchConfigurations(),
        ]

    def describe(self) -> str:
        """Whether the group is scoped, for introspection."""
        return f'GroupAction(scoped={self.scoped})'

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        """The grouped actions."""
        return list(self.actions)


class IncludeLaunchDescription(Action):
    """Includes another launch description (usually a file), setting its arguments. It
    remembers the launch files that led to it, so that reading what it includes later (it
    runs after the file holding it was read) can tell a cycle."""

    def __init__(
        self,
        launch_description_source: LaunchDescriptionSource
        | LaunchDescription
        | SomeSubstitutionsType
        | Path,
        *,
        launch_arguments: Iterable[tuple[SomeSubstitutionsType, SomeSubstitutionsType]]
        | SubstitutionMapping
        | None = None,
        **kwargs: Unpack[ActionOptions],
    ) -> None:
        super().__init__(**kwargs)
        if isinstance(launch_description_source, LaunchDescription):
            launch_description_source = LaunchDescriptionSource(launch_description_source)
        elif not isinstance(launch_description_source, LaunchDescriptionSource):
            # a file's path as such, as launch takes it since Iron (urdf_launch's includes)
            launch_description_source = AnyLaunchDescriptionSource(launch_description_source)
        self.launch_description_source = launch_description_source
        items = (
            launch_arguments.items()
            if isinstance(launch_arguments, Mapping)
            else (launch_arguments or [])
        )
        self.launch_arguments = [
            (normalize_to_list_of_substitutions(k), normalize_to_list_of_substitutions(v))
            for k, v in items
        ]
        self._chain = include_chain()

    def execute(self, context: LaunchContext) -> Entities | None:
        """The included description, after setting its launch arguments and checking that
        every argument it requires is given."""
        values = [
            (perform_substitutions(context, key), perform_substitutions(context, value))
            for key, value in self.launch_arguments
        ]
        with reading_from(self._chain), giving(values):
            description = self.launch_description_source.get_launch_description(context)
        location = getattr(self.launch_description_source, 'location', None)
        if isinstance(location, str):
            key = include_key(os.path.realpath(location), values)
            if key in self._chain:
                real = os.path.realpath(location)
                with reading_from(self._chain), giving(values), including(real):
                    pass  # (a source read before, included again: says the cycle)
        given = []
        for name, value in values:
            context.launch_configurations[name] = value
            given.append(name)
        for arg, conditional, via in declared_arguments(description):
            if conditional or arg.default_value is not None:
                continue
            names = {*given, *context.launch_configurations}
            for include in via:  # an include on the way may give it
                names.update(include.argument_names_without_context())
            if arg.name not in names:
                raise LaunchError(
                    f"Included launch description missing required argument '{arg.name}' "
                    f"(description: '{arg.description}'), given: [{', '.join(given)}]"
                )
        return [description]

    def describe(self) -> str:
        """Where the description comes from, for introspection."""
        return f'IncludeLaunchDescription({self.launch_description_source.describe()})'

    def argument_names_without_context(self) -> list[str]:
        """The names of the arguments it gives that are plain text."""
        return [
            ''.join(s.text for s in key if isinstance(s, TextSubstitution))
            for key, _value in self.launch_arguments
            if all(isinstance(s, TextSubstitution) for s in key)
        ]

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        """The included description when it can be read without running the launch."""
        source = self.launch_description_source
        try:
            with reading_from(self._chain):
                found = source.try_get_launch_description_without_context()
                if found is None:
                    found = source.get_launch_description(LaunchContext())
        except Exception:  # a path built from a launch argument (unknown until run), a cycle
            return []
        return [found]


class TimerAction(Action):
    """Visits `actions` after `period` seconds (cancelled by shutdown unless told not)."""

    def __init__(
        self,
        *,
        period: float | SomeSubstitutionsType,
        actions: Iterable[LaunchDescriptionEntity],
        cancel_on_shutdown: bool = True,
        **kwargs: Unpack[ActionOptions],
    ) -> None:
        super().__init__(**kwargs)
        self.period = normalize_to_list_of_substitutions(period)
        self.actions = list(actions)
        self.cancel_on_shutdown = cancel_on_shutdown
        self.cancelled = False

    def execute(self, context: LaunchContext) -> Entities | None:
        """Schedule its actions with the launch service, in the scope it was reached in."""
        seconds = seconds_of(context, self.period, 'TimerAction period')
        # its actions run later, in the scope of now (the namespace, parameters and launch
        # configurations of an enclosing group, as launch does since ros2/launch#836)
        context.service.add_timer(self, seconds, context.capture_locals(), context.scope.copy())
        return None

    def cancel(self) -> None:
        """Drop the pending actions (they will not run)."""
        self.cancelled = True

    def describe(self) -> str:
        """The period, for introspection."""
        return f'TimerAction(period={describe_substitutions(self.period)})'

    def describe_conditional_sub_entities(
        self,
    ) -> list[tuple[str, list[LaunchDescriptionEntity]]]:
        """The actions, run only when the period has passed."""
        return [(f'after {describe_substitutions(self.period)} s', list(self.actions))]


class RegisterEventHandler(Action):
    """Registers an event handler for the rest of the launch."""

    def __init__(self, event_handler: EventHandler, **kwargs: Unpack[ActionOptions]) -> None:
        super().__init__(**kwargs)
        self.event_handler = event_handler

    def execute(self, context: LaunchContext) -> Entities | None:
        """Add the handler to the context (newest first)."""
        context.register_event_handler(self.event_handler)
        return None

    def describe(self) -> str:
        """The handler's description, for introspection."""
        return f'RegisterEventHandler({self.event_handler.describe()})'

    def describe_conditional_sub_entities(
        self,
    ) -> list[tuple[str, list[LaunchDescriptionEntity]]]:
        """The entities the handler visits when its event happens."""
        return [(self.event_handler.describe(), self.event_handler.describe_sub_entities())]


class UnregisterEventHandler(Action):
    """Removes an event handler."""

    def __init__(self, event_handler: EventHandler, **kwargs: Unpack[ActionOptions]) -> None:
        super().__init__(**kwargs)
        self.event_handler = event_handler

    def execute(self, context: LaunchContext) -> Entities | None:
        """Remove the handler from the context."""
        context.unregister_event_handler(self.event_handler)
        return None


class EmitEvent(Action):
    """Emits an event (e.g. ``Shutdown()``) for the handlers."""

    def __init__(self, *, event: Event, **kwargs: Unpack[ActionOptions]) -> None:
        super().__init__(**kwargs)
        self.event = event

    def execute(self, context: LaunchContext) -> Entities | None:
        """Hand the event to the context's handlers."""
        context.emit_event_sync(self.event)
        return None

    def describe(self) -> str:
        """The event's name, for introspection."""
        return f'EmitEvent({type(self.event).__name__})'


class LogInfo(Action):
    """Logs a line as `[INFO] [launch.user]: …`."""

    def __init__(self, *, msg: SomeSubstitutionsType, **kwargs: Unpack[ActionOptions]) -> None:
        super().__init__(**kwargs)
        self.msg = normalize_to_list_of_substitutions(msg)

    def execute(self, context: LaunchContext) -> Entities | None:
        """Log the performed message at INFO from `launch.user`."""
        context.service.log('INFO', 'launch.user', perform_substitutions(context, self.msg))
        return None

    def describe(self) -> str:
        """The message, for introspection."""
        return f'LogInfo({describe_substitutions(self.msg)})'


class Shutdown(EmitEvent):
    """Shuts the launch down (every process is stopped)."""

    def __init__(
        self, *, reason: SomeSubstitutionsType = 'reason not given', **kwargs: Unpack[ActionOptions]
    ) -> None:
        self.reason = normalize_to_list_of_substitutions(reason)
        super().__init__(event=ShutdownEvent(reason='reason not given'), **kwargs)

    def execute(self, context: LaunchContext) -> Entities | None:
        """Start the launch's shutdown with the performed reason."""
        self.event = ShutdownEvent(reason=perform_substitutions(context, self.reason))
        return super().execute(context)
