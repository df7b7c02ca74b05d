"""Launch descriptions and the actions they are made of.

An *action* is an entity (anything a launch description holds, :mod:`.entity`) with an
optional condition, checked when the action is reached.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Protocol, TypedDict, runtime_checkable

from .conditions import Condition
from .entity import Entities, LaunchDescriptionEntity
from .errors import LaunchError
from .events import Event, ExecutionComplete
from .events import Shutdown as ShutdownEvent
from .substitutions import (
    SomeSubstitutionsType,
    Substitution,
    SubstitutionMapping,
    TextSubstitution,
    describe_substitutions,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from .context import LaunchContext
    from .event_handlers import EventHandler

__all__ = [
    'Action',
    'AppendEnvironmentVariable',
    'DeclareLaunchArgument',
    'EmitEvent',
    'GroupAction',
    'IncludeLaunchDescription',
    'LaunchDescription',
    'LaunchDescriptionEntity',
    'LogInfo',
    'OpaqueFunction',
    'PopLaunchConfigurations',
    'PushLaunchConfigurations',
    'RegisterEventHandler',
    'SetEnvironmentVariable',
    'SetLaunchConfiguration',
    'Shutdown',
    'TimerAction',
    'UnregisterEventHandler',
    'UnsetEnvironmentVariable',
    'UnsetLaunchConfiguration',
]


class ActionOptions(TypedDict, total=False):
    """The keywords every action takes (what subclasses pass on to :class:`Action`)."""

    condition: Condition | None


class Action(LaunchDescriptionEntity):
    """An entity that runs when reached, if its condition (if any) holds."""

    # a process completes when it exits, not when it was started
    completes_on_execute = True

    def __init__(self, *, condition: Condition | None = None) -> None:
        self.__condition = condition

    @property
    def condition(self) -> Condition | None:
        """The condition checked when the action is reached (None: always runs)."""
        return self.__condition

    def visit(self, context: LaunchContext) -> Entities | None:
        """Run the action if its condition holds, announcing its completion to any handler."""
        if self.__condition is not None and not self.__condition.evaluate(context):
            return None
        entities = self.execute(context)
        if self.completes_on_execute:
            done = ExecutionComplete(action=self)
            if any(True for _ in context.handlers_for(done)):
                context.emit_event_sync(done)
        return entities

    def execute(self, context: LaunchContext) -> Entities | None:
        """The action's work (the condition has been checked)."""
        return None

    def describe(self) -> str:
        """The action's class name, as introspection lists it."""
        return f'{type(self).__name__}()'


class _PushLocals(LaunchDescriptionEntity):
    def __init__(self, values: Mapping[str, object]) -> None:
        self.values = values

    def visit(self, context: LaunchContext) -> Entities | None:
        context.push_locals(self.values)
        return None


class _PopLocals(LaunchDescriptionEntity):
    def visit(self, context: LaunchContext) -> Entities | None:
        context.pop_locals()
        return None


class LaunchDescription(LaunchDescriptionEntity):
    """An ordered list of entities: what a launch file returns."""

    def __init__(
        self,
        initial_entities: Iterable[LaunchDescriptionEntity] | None = None,
        *,
        deprecated_reason: str | None = None,
    ) -> None:
        self.entities: list[LaunchDescriptionEntity] = list(initial_entities or [])
        self.deprecated_reason = deprecated_reason
        self.source_path: str | None = None  # set by the loader of a launch file

    def visit(self, context: LaunchContext) -> Entities | None:
        """Unfold into its entities (warning first when the description is deprecated)."""
        if self.deprecated_reason is not None and context.has_service:
            where = self.source_path or 'a launch description'
            context.service.log(
                'WARNING', 'launch', f'{where} is deprecated: {self.deprecated_reason}'
            )
        if self.source_path is None:
            return list(self.entities)
        frame = {
            'current_launch_file_path': self.source_path,
            'current_launch_file_directory': os.path.dirname(self.source_path),
        }
        return [_PushLocals(frame), *self.entities, _PopLocals()]

    def add_entity(self, entity: LaunchDescriptionEntity) -> None:
        """Append an entity (launch files build descriptions step by step)."""
        self.entities.append(entity)

    def add_action(self, action: Action) -> None:
        """Append an action (launch's older name for add_entity)."""
        self.entities.append(action)

    def describe(self) -> str:
        """A one-line summary for `launch -p`."""
        where = f' ({self.source_path})' if self.source_path else ''
        return f'LaunchDescription{where}'

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        """The entities it holds, in order."""
        return list(self.entities)

    def get_launch_arguments(
        self, conditional_inclusion: bool = False
    ) -> list[DeclareLaunchArgument]:
        """Every DeclareLaunchArgument reachable from here (see :func:`launch_arguments`)."""
        return [arg for arg, _conditional in launch_arguments(self)]


class LaunchDescriptionSource:
    """Where an included launch description comes from: here, one given directly; the
    launch files of :mod:`.sources` load theirs on first use."""

    method = 'launch description'

    def __init__(
        self,
        launch_description: LaunchDescription | None = None,
        location: str = '<string>',
        method: str | None = None,
    ) -> None:
        self._description = launch_description
        self.location = location
        if method is not None:
            self.method = method

    def try_get_launch_description_without_context(self) -> LaunchDescription | None:
        """The description if it is already known (introspection needs no context)."""
        return self._description

    def get_launch_description(self, context: LaunchContext) -> LaunchDescription:
        """The description, loading it in this context if needed."""
        if self._description is None:
            raise LaunchError('launch description source has no launch description')
        return self._description

    def describe(self) -> str:
        """Where the description comes from, for introspection."""
        return f'{self.method} at {self.location!r}'


# -- arguments and configurations ----------------------------------------------------------------


class DeclareLaunchArgument(Action):
    """A launch argument (`name:=value` on the command line, or given by an include), with
    an optional default and allowed choices."""

    def __init__(
        self,
        name: str,
        *,
        default_value: SomeSubstitutionsType | None = None,
        description: str | None = None,
        choices: Sequence[str] | None = None,
        **kwargs: Unpack[ActionOptions],
    ) -> None:
        super().__init__(**kwargs)
        self.name = name
        self.default_value = (
            None if default_value is None else normalize_to_list_of_substitutions(default_value)
        )
        self.description = description if description is not None else 'no description given'
        self.choices = list(choices) if choices is not None else None
        if self.choices is not None and self.default_value is not None:
            texts = [s.text for s in self.default_value if isinstance(s, TextSubstitution)]
            if len(texts) == len(self.default_value) and ''.join(texts) not in self.choices:
                raise LaunchError(
                    f"default value '{''.join(texts)}' of launch argument '{name}' is not "
                    f'one of its choices {self.choices}'
                )

    def execute(self, context: LaunchContext) -> Entities | None:
        """Set the argument's default unless the caller gave it a value; check its choices."""
        if self.name not in context.launch_configurations:
            if self.default_value is None:
                raise LaunchError(
                    f'Required launch argument "{self.name}" (description: '
                    f'"{self.description}") was not provided'
                )
            context.launch_configurations[self.name] = perform_substitutions(
                context, self.default_value
            )
        value = context.launch_configurations[self.name]
        if self.choices is not None and value not in self.choices:
            raise LaunchError(
                f'Argument "{self.name}" provided value "{value}" is not valid. '
                f'Valid options are: {self.choices}'
            )
        return None

    def describe(self) -> str:
        """The argument's name, as `launch -s` lists it."""
        default = (
            f', default={describe_substitutions(self.default_value)}'
            if self.default_value is not None
            else ''
        )
        return f'DeclareLaunchArgument({self.name!r}{default})'


class _Setting(Action):
    """An action on one named entry of a scope's table (its launch configurations or its
    environment): the subclasses say which table and what they do to the entry."""

    def __init__(self, name: SomeSubstitutionsType, **kwargs: Unpack[ActionOptions]) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)

    def _table(self, context: LaunchContext) -> dict[str, str]:
        raise NotImplementedError


class _Set(_Setting):
    def __init__(
        self,
        name: SomeSubstitutionsType,
        value: SomeSubstitutionsType,
        **kwargs: Unpack[ActionOptions],
    ) -> None:
        super().__init__(name, **kwargs)
        self.value = normalize_to_list_of_substitutions(value)

    def execute(self, context: LaunchContext) -> Entities | None:
        """Store the performed value under the performed name in the current scope."""
        name = perform_substitutions(context, self.name)
        self._table(context)[name] = perform_substitutions(context, self.value)
        return None


class _Unset(_Setting):
    def execute(self, context: LaunchContext) -> Entities | None:
        """Remove the entry from the current scope (if set)."""
        self._table(context).pop(perform_substitutions(context, self.name), None)
        return None


class _Configurations:
    def _table(self, context: LaunchContext) -> dict[str, str]:
        return context.launch_configurations


class _Environment:
    def _table(self, context: LaunchContext) -> dict[str, str]:
        return context.environment


class SetLaunchConfiguration(_Configurations, _Set):
    """Sets a launch configuration in the current scope."""

    def describe(self) -> str:
        """Name and value, for introspection."""
        return (
            f'SetLaunchConfiguration({describe_substitutions(self.name)}, '
            f'{describe_substitutions(self.value)})'
        )


class UnsetLaunchConfiguration(_Configurations, _Unset):
    """Removes a launch configuration from the current scope."""


class PushLaunchConfigurations(Action):
    """Starts a scope: what is set until the matching pop is forgotten then."""

    def __init__(self, *, forwarding: bool = True, **kwargs: Unpack[ActionOptions]) -> None:
        super().__init__(**kwargs)
        self.forwarding = forwarding

    def execute(self, context: LaunchContext) -> Entities | None:
        """Open a scope, so that what follows cannot change the outer one."""
        context.push_scope(forwarding=self.forwarding)
        return None


class PopLaunchConfigurations(Action):
    """Ends the scope the matching push started."""

    def execute(self, context: LaunchContext) -> Entities | None:
        """Close the scope opened by the matching push."""
        context.pop_scope()
        return None


class SetEnvironmentVariable(_Environment, _Set):
    """Sets a variable in the environment of processes started after it (in this scope)."""


class UnsetEnvironmentVariable(_Environment, _Unset):
    """Removes a variable from the environment of processes started after it."""


class AppendEnvironmentVariable(Action):
    """Appends (or prepends) a value to a path-like environment variable."""

    def __init__(
        self,
        name: SomeSubstitutionsType,
        value: SomeSubstitutionsType,
        *,
        prepend: bool = False,
        separator: str = os.pathsep,
        **kwargs: Unpack[ActionOptions],
    ) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)
        self.value = normalize_to_list_of_substitutions(value)
        self.prepend = prepend
        self.separator = separator

    def execute(self, context: LaunchContext) -> Entities | None:
        """Add to the variable (before or after its value) with the separator."""
        name = perform_substitutions(context, self.name)
        value = perform_substitutions(context, self.value)
        old = context.environment.get(name, '')
        if not old:
            new = value
        elif self.prepend:
            new = value + self.separator + old
        else:
            new = old + self.separator + value
        context.environment[name] = new
        return None


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
    """Includes another launch description (usually a file), setting its arguments."""

    def __init__(
        self,
        launch_description_source: LaunchDescriptionSource | LaunchDescription,
        *,
        launch_arguments: Iterable[tuple[SomeSubstitutionsType, SomeSubstitutionsType]]
        | SubstitutionMapping
        | None = None,
        **kwargs: Unpack[ActionOptions],
    ) -> None:
        super().__init__(**kwargs)
        if isinstance(launch_description_source, LaunchDescription):
            launch_description_source = LaunchDescriptionSource(launch_description_source)
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

    def execute(self, context: LaunchContext) -> Entities | None:
        """The included description, after setting its launch arguments and checking that
        every argument it requires is given."""
        description = self.launch_description_source.get_launch_description(context)
        given = []
        for key, value in self.launch_arguments:
            name = perform_substitutions(context, key)
            context.launch_configurations[name] = perform_substitutions(context, value)
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
        from .context import LaunchContext

        source = self.launch_description_source
        try:
            found = source.try_get_launch_description_without_context()
            if found is None:
                found = source.get_launch_description(LaunchContext())
        except Exception:  # e.g. a path built from a launch argument: unknown until run
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


class OpaqueFunction(Action):
    """Calls `function(context, *args, **kwargs)`; what it returns is visited next."""

    def __init__(
        self,
        *,
        function: Callable[..., LaunchDescriptionEntity | Iterable[LaunchDescriptionEntity] | None],
        args: Sequence[object] | None = None,
        kwargs: Mapping[str, object] | None = None,
        **action_kwargs: Unpack[ActionOptions],
    ) -> None:
        super().__init__(**action_kwargs)
        self.function = function
        self.args = list(args or [])
        self.kwargs = dict(kwargs or {})

    def execute(self, context: LaunchContext) -> Entities | None:
        """Call the function; what it returns is visited next."""
        result = self.function(context, *self.args, **self.kwargs)
        if result is None:
            return None
        if isinstance(result, LaunchDescriptionEntity):
            return [result]
        return list(result)

    def describe(self) -> str:
        """The function's name, for introspection."""
        name = getattr(self.function, '__name__', repr(self.function))
        return f'OpaqueFunction({name})'


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


def seconds_of(context: LaunchContext, subs: Sequence[Substitution], what: str) -> float:
    """A duration given as substitutions, performed: a number of seconds, never negative
    (`what` names it in the error)."""
    text = perform_substitutions(context, subs)
    try:
        value = float(text)
    except ValueError:
        raise LaunchError(f"{what} '{text}' is not a number") from None
    if value < 0:
        raise LaunchError(f'{what} {value} is negative')
    return value


def path_of(value: SomeSubstitutionsType | Path, context: LaunchContext) -> str:
    """A path given as text, Path or substitutions, performed."""
    if isinstance(value, Path):
        return str(value)
    return perform_substitutions(context, normalize_to_list_of_substitutions(value))


# -- what a description declares -------------------------------------------------------------------


@runtime_checkable
class GivesArguments(Protocol):
    """An entity that gives the description below it launch arguments (an include)."""

    def argument_names_without_context(self) -> list[str]:
        """The names of the arguments it gives that are plain text."""
        ...


def launch_arguments(
    root: LaunchDescriptionEntity,
) -> list[tuple[DeclareLaunchArgument, bool]]:
    """(argument, only used under some condition) for every DeclareLaunchArgument reachable
    from `root`, included files too, first declaration of a name only."""
    return [(arg, conditional) for arg, conditional, _via in declared_arguments(root)]


def declared_arguments(
    root: LaunchDescriptionEntity,
) -> list[tuple[DeclareLaunchArgument, bool, list[GivesArguments]]]:
    """Like :func:`launch_arguments`, with the includes each argument is reached through
    (those may give it its value)."""
    found: dict[str, tuple[DeclareLaunchArgument, bool, list[GivesArguments]]] = {}

    def walk(
        entities: Iterable[LaunchDescriptionEntity],
        conditional: bool,
        via: list[GivesArguments],
    ) -> None:
        for entity in entities:
            cond = conditional or (isinstance(entity, Action) and entity.condition is not None)
            if isinstance(entity, DeclareLaunchArgument) and entity.name not in found:
                found[entity.name] = (entity, cond, via)
            inner = [*via, entity] if isinstance(entity, GivesArguments) else via
            walk(entity.describe_sub_entities(), cond, inner)
            for _label, subs in entity.describe_conditional_sub_entities():
                walk(subs, True, inner)

    walk([root], False, [])
    return list(found.values())
