"""The launch context: what actions read and change while a launch runs.

Launch configurations, the environment for new processes, the ROS namespace, global
parameters and remappings live in a *scope*; a scoped group (GroupAction) pushes a copy and
pops it afterwards, so nothing set inside leaks out. *Locals* (the current launch file, the
event being handled) live in a stack of frames pushed for the stretch that needs them.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Protocol, TypeAlias

from .events import Event, ProcessDetails
from .process_spec import ProcessSpec

if TYPE_CHECKING:
    from ros2lite.pkg.index import PackageIndex

__all__ = ['LaunchContext', 'ParameterData', 'Scope']

# what a node gets for one parameter: a YAML scalar, a list, or nothing (global parameters
# live in a scope; :mod:`.ros` reads and writes them)
ParameterData: TypeAlias = 'bool | int | float | str | list[object] | None'


@dataclass
class Scope:
    """What a scoped group isolates."""

    configurations: dict[str, str] = field(default_factory=dict)
    environment: dict[str, str] = field(default_factory=dict)
    ros_namespace: str | None = None
    # (name, value) pairs and parameter file paths, in the order they were set
    global_params: list[tuple[str, ParameterData] | Path] = field(default_factory=list)
    remaps: list[tuple[str, str]] = field(default_factory=list)

    def copy(self, *, forwarding: bool = True) -> Scope:
        """A copy for a nested scope; without `forwarding`, launch configurations start empty."""
        return Scope(
            dict(self.configurations) if forwarding else {},
            dict(self.environment),
            self.ros_namespace,
            list(self.global_params),
            list(self.remaps),
        )


# -- what the context holds, by shape ------------------------------------------------------------
# Entities, substitutions, event handlers and the launch service all take the context as an
# argument, so it cannot import them: it names here the little it (and the service, through
# it) asks of each. The classes named in each docstring are the real ones.


class SubstitutionLike(Protocol):
    """A :class:`~ros2lite.launch.substitutions.Substitution`: it becomes text in a context."""

    def perform(self, context: LaunchContext) -> str:
        """The text, in this context."""
        ...


class EntityLike(Protocol):
    """A :class:`~ros2lite.launch.entity.LaunchDescriptionEntity`: visiting it in a context
    does its work and may give more entities to visit."""

    def visit(self, context: LaunchContext) -> Sequence[EntityLike] | None:
        """Do the entity's work; return entities to visit next."""
        ...


class EventHandlerLike(Protocol):
    """An :class:`~ros2lite.launch.event_handlers.EventHandler`, as the context keeps it."""

    captured_locals: dict[str, object]

    def matches(self, event: Event) -> bool:
        """Whether it reacts to `event`."""
        ...

    def handle(self, event: Event, context: LaunchContext) -> Sequence[EntityLike] | None:
        """The entities to visit for `event`."""
        ...


class TimerLike(Protocol):
    """A :class:`~ros2lite.launch.flow.TimerAction`, as the service holds it until due."""

    @property
    def actions(self) -> Sequence[EntityLike]:
        """What to visit when it fires."""
        ...

    @property
    def cancelled(self) -> bool:
        """Whether it was cancelled (it will not fire)."""
        ...

    @property
    def cancel_on_shutdown(self) -> bool:
        """Whether shutting down cancels it."""
        ...

    def cancel(self) -> None:
        """Drop its pending actions."""
        ...


class ProcessActionLike(Protocol):
    """An :class:`~ros2lite.launch.execute.ExecuteProcess`, as the service runs its process."""

    process_details: ProcessDetails | None
    return_code: int | None
    respawn_count: int

    @property
    def env(self) -> Sequence[object] | None:
        """The process' own environment, if given (None: the launch's)."""
        ...

    @property
    def respawn_delay(self) -> float | None:
        """Seconds to wait before a respawn."""
        ...

    def should_respawn(self, context: LaunchContext) -> bool:
        """Whether to start the process again after it exited."""
        ...

    def describe(self) -> str:
        """A short name for listings."""
        ...


class LaunchServiceLike(Protocol):
    """What actions ask of the :class:`~ros2lite.launch.service.LaunchService` running them."""

    def log(self, level: str, name: str, msg: str) -> None:
        """Write a launch log line."""
        ...

    def add_timer(
        self, action: TimerLike, seconds: float, frame: dict[str, object], scope: Scope
    ) -> None:
        """Visit the timer's actions in `seconds`, with these locals and in this scope."""
        ...

    def add_temp_file(self, path: str) -> None:
        """A file to delete when the launch ends."""
        ...

    def start_process(self, action: ProcessActionLike, spec: ProcessSpec) -> None:
        """Start the action's process."""
        ...


class _Locals:
    """Attribute access to the merged local frames (`context.locals.event`)."""

    _context: LaunchContext

    def __init__(self, context: LaunchContext) -> None:
        object.__setattr__(self, '_context', context)

    def __getattr__(self, name: str) -> object:
        merged = self._context.get_locals_as_dict()
        if name in merged:
            return merged[name]
        raise AttributeError(f"context.locals has no '{name}'")


class LaunchContext:
    """Shared state of one launch (see the module doc)."""

    def __init__(
        self,
        *,
        argv: Sequence[str] = (),
        noninteractive: bool = False,
        environment: Mapping[str, str] | None = None,
    ) -> None:
        self.argv = list(argv)
        self.noninteractive = noninteractive
        self._scopes = [Scope(environment=dict(os.environ if environment is None else environment))]
        self._frames: list[dict[str, object]] = [{}]
        self._handlers: list[EventHandlerLike] = []
        self._anonymous: dict[str, str] = {}
        self._index: PackageIndex | None = None
        self.is_shutdown = False
        self.output_override: str | None = None  # every process' output mode, if set
        # set by the launch service that runs this context
        self.emit_event_sync: Callable[[Event], None] = self._no_service
        self._service: LaunchServiceLike | None = None

    @staticmethod
    def _no_service(_event: Event) -> None:
        raise RuntimeError('this launch context is not run by a launch service')

    @property
    def has_service(self) -> bool:
        """Whether a launch service runs this context (actions may be visited without one)."""
        return self._service is not None

    @property
    def service(self) -> LaunchServiceLike:
        """The launch service running this context: where processes, timers and log lines go."""
        if self._service is None:
            raise RuntimeError('this launch context is not run by a launch service')
        return self._service

    @service.setter
    def service(self, service: LaunchServiceLike) -> None:
        self._service = service

    def emit_event(self, event: Event) -> None:
        """Queue `event` for the handlers (same as :meth:`emit_event_sync` here)."""
        self.emit_event_sync(event)

    # -- scopes ----------------------------------------------------------------------------------
    @property
    def scope(self) -> Scope:
        """The innermost scope: where actions read and write settings."""
        return self._scopes[-1]

    @property
    def launch_configurations(self) -> dict[str, str]:
        """The launch configurations visible now."""
        return self.scope.configurations

    @property
    def environment(self) -> dict[str, str]:
        """The environment new processes get now."""
        return self.scope.environment

    def push_scope(self, *, forwarding: bool = True, saved: Scope | None = None) -> None:
        """A new innermost scope: a copy of the current one, or of `saved` (deferred work,
        such as a timer's actions, runs in the scope it was scheduled from)."""
        self._scopes.append((self.scope if saved is None else saved).copy(forwarding=forwarding))

    def pop_scope(self) -> None:
        """Return to the enclosing scope (what the nested one set is dropped)."""
        if len(self._scopes) == 1:
            raise RuntimeError('pop_scope() without a matching push_scope()')
        self._scopes.pop()

    # -- locals ----------------------------------------------------------------------------------
    @property
    def locals(self) -> _Locals:
        """Attribute access to the locals (`context.locals.event`)."""
        return _Locals(self)

    def get_locals_as_dict(self) -> dict[str, object]:
        """Every local frame merged, innermost last."""
        merged: dict[str, object] = {}
        for frame in self._frames:
            merged.update(frame)
        return merged

    def extend_locals(self, values: Mapping[str, object]) -> None:
        """Add values to the innermost frame."""
        self._frames[-1].update(values)

    def push_locals(self, values: Mapping[str, object] | None = None) -> None:
        """A new innermost frame holding `values`."""
        self._frames.append(dict(values or {}))

    def pop_locals(self) -> None:
        """Drop the innermost frame (the outermost one stays)."""
        if len(self._frames) > 1:
            self._frames.pop()

    def capture_locals(self) -> dict[str, object]:
        """The locals now, to restore later around deferred work (timers, handlers)."""
        return self.get_locals_as_dict()

    # -- event handlers --------------------------------------------------------------------------
    def register_event_handler(self, handler: EventHandlerLike, append: bool = False) -> None:
        """Newest first, as launch does, unless `append`."""
        handler.captured_locals = self.capture_locals()
        if append:
            self._handlers.append(handler)
        else:
            self._handlers.insert(0, handler)

    def unregister_event_handler(self, handler: EventHandlerLike) -> None:
        """Remove the handler, if registered."""
        if handler in self._handlers:
            self._handlers.remove(handler)

    @property
    def event_handlers(self) -> list[EventHandlerLike]:
        """The registered handlers, in the order they are asked."""
        return list(self._handlers)

    def handlers_for(self, event: Event) -> Iterator[EventHandlerLike]:
        """The handlers that accept `event`, in order."""
        for handler in list(self._handlers):
            if handler.matches(event):
                yield handler

    # -- values ----------------------------------------------------------------------------------
    def perform_substitution(self, substitution: SubstitutionLike) -> str:
        """The text of one substitution in this context."""
        return substitution.perform(self)

    @property
    def package_index(self) -> PackageIndex:
        """The package index as this launch sees it (read once per launch)."""
        if self._index is None:
            from ros2lite.pkg.index import PackageIndex

            self._index = PackageIndex(self.environment)
        return self._index

    def use_package_index(self, index: PackageIndex) -> None:
        """Answer package questions from `index` (one the caller has already read)."""
        self._index = index

    def anonymous_name(self, name: str, make: Callable[[], str]) -> str:
        """The same generated name for `name` throughout one launch."""
        if name not in self._anonymous:
            self._anonymous[name] = make()
        return self._anonymous[name]
