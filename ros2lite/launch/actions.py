"""Launch descriptions and the actions they are made of.

An *action* is an entity (anything a launch description holds, :mod:`.entity`) with an
optional condition, checked when the action is reached.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextvars import ContextVar
from pathlib import Path
from typing import TYPE_CHECKING, Protocol, TypedDict, runtime_checkable

from .conditions import Condition
from .entity import Entities, LaunchDescriptionEntity
from .errors import LaunchError
from .events import ExecutionComplete
from .substitutions import (
    SomeSubstitutionsType,
    Substitution,
    TextSubstitution,
    describe_substitutions,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from .context import LaunchContext

__all__ = [
    'Action',
    'AppendEnvironmentVariable',
    'DeclareLaunchArgument',
    'LaunchDescription',
    'LaunchDescriptionEntity',
    'OpaqueFunction',
    'PopLaunchConfigurations',
    'PushLaunchConfigurations',
    'SetEnvironmentVariable',
    'SetLaunchConfiguration',
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


MAX_INCLUDE_DEPTH = 64
"""Launch files nested deeper than this are refused (a runaway, not a design)."""

# the launch files being read, outermost first: what led to the file read now, each with
# the launch arguments its include gave (a file may include itself with other arguments:
# `n:=n-1` until a condition ends it, which is no cycle)
_INCLUDES: ContextVar[tuple[str, ...]] = ContextVar('ros2lite_launch_includes', default=())
# the arguments of the include about to read its file
_GIVEN: ContextVar[str] = ContextVar('ros2lite_launch_given', default='')


def include_key(path: str, arguments: Iterable[tuple[str, str]] = ()) -> str:
    """How the chain knows a file read with some arguments: the same file with the same
    arguments again is a cycle, with others it is recursion a condition may end."""
    given = ' '.join(f'{k}:={v}' for k, v in sorted(arguments))
    return f'{path} [{given}]' if given else path


@contextlib.contextmanager
def giving(arguments: Iterable[tuple[str, str]]) -> Iterator[None]:
    """While an include reads its file: the launch arguments it gives it."""
    token = _GIVEN.set(include_key('', arguments).strip())
    try:
        yield
    finally:
        _GIVEN.reset(token)


@contextlib.contextmanager
def including(path: str) -> Iterator[None]:
    """While the launch file `path` (resolved) is read: refuse it when it is already on the
    way to itself with the same arguments (a cycle would load forever) or nested too deep,
    in one line."""
    chain = _INCLUDES.get()
    given = _GIVEN.get()
    key = f'{path} {given}' if given else path
    if key in chain:
        loop = [*chain[chain.index(key) :], key]
        if len(loop) == 2:
            raise LaunchError(f"launch file '{key}' includes itself")
        raise LaunchError(f'launch files include each other in a cycle: {" -> ".join(loop)}')
    path = key
    if len(chain) >= MAX_INCLUDE_DEPTH:
        raise LaunchError(
            f'launch files are nested more than {MAX_INCLUDE_DEPTH} deep '
            f"(… {' -> '.join(chain[-3:])} -> {path})"
        )
    token = _INCLUDES.set((*chain, path))
    consumed = _GIVEN.set('')  # the arguments were this file's, not those it reads in turn
    try:
        yield
    finally:
        _GIVEN.reset(consumed)
        _INCLUDES.reset(token)


def include_chain() -> tuple[str, ...]:
    """The launch files being read now, outermost first (what an include made now keeps)."""
    return _INCLUDES.get()


@contextlib.contextmanager
def reading_from(chain: tuple[str, ...]) -> Iterator[None]:
    """Read with `chain` as the files that led here (an include runs after its file was
    read, so it puts back the chain it was made under)."""
    token = _INCLUDES.set(chain)
    try:
        yield
    finally:
        _INCLUDES.reset(token)
