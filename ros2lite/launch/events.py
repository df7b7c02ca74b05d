"""Events: what happens while a launch runs, delivered to registered event handlers."""

from __future__ import annotations

import signal as _signal
from collections.abc import Callable
from typing import TYPE_CHECKING, Protocol, TypedDict

if TYPE_CHECKING:
    from typing_extensions import Unpack

__all__ = [
    'Event',
    'ExecutionComplete',
    'ProcessEvent',
    'ProcessExited',
    'ProcessIO',
    'ProcessStarted',
    'ProcessStderr',
    'ProcessStdout',
    'Shutdown',
    'ShutdownProcess',
    'SignalProcess',
    'matches_action',
]


class ActionLike(Protocol):
    """The action an event is about (a :class:`ros2lite.launch.actions.Action`), by the one
    thing every action can do: describe itself. Events only carry their action, to be matched
    by identity, so this module names its shape instead of importing the actions that emit
    them. (Not in ``__all__``: launch's ``events`` has no such name.)"""

    def describe(self) -> str:
        """A short name for listings."""
        ...


class Event:
    """Base of every event."""

    name = 'launch.events.Event'


class Shutdown(Event):
    """The launch is stopping: every process is stopped, pending timers are cancelled."""

    name = 'launch.events.Shutdown'

    def __init__(self, *, reason: str = 'reason not given', due_to_sigint: bool = False) -> None:
        self.reason = reason
        self.due_to_sigint = due_to_sigint


class ExecutionComplete(Event):
    """An action finished executing (a process: when it exited)."""

    name = 'launch.events.ExecutionComplete'

    def __init__(self, *, action: ActionLike) -> None:
        self.action = action


class ProcessDetails(TypedDict):
    """What every event about a process carries (the launch service fills it in once)."""

    action: ActionLike
    name: str
    cmd: list[str]
    cwd: str | None
    env: dict[str, str] | None
    pid: int


class ProcessEvent(Event):
    """Something about one process: which action, its name, command, cwd, env and pid."""

    name = 'launch.events.process.ProcessEvent'

    def __init__(
        self,
        *,
        action: ActionLike,
        name: str,
        cmd: list[str],
        cwd: str | None = None,
        env: dict[str, str] | None = None,
        pid: int = 0,
    ) -> None:
        self.action = action
        self.process_name = name
        self.cmd = cmd
        self.cwd = cwd
        self.env = env
        self.pid = pid

    @property
    def execute_process_action(self) -> ActionLike:
        """The action that started the process (launch's name for `action`)."""
        return self.action


class ProcessStarted(ProcessEvent):
    """The process has started (its pid is known)."""

    name = 'launch.events.process.ProcessStarted'


class ProcessExited(ProcessEvent):
    """The process has exited with `returncode`."""

    name = 'launch.events.process.ProcessExited'

    def __init__(self, *, returncode: int, **kwargs: Unpack[ProcessDetails]) -> None:
        super().__init__(**kwargs)
        self.returncode = returncode


class ProcessIO(ProcessEvent):
    """A line a process wrote (`text` holds its bytes, newline included)."""

    name = 'launch.events.process.ProcessIO'

    def __init__(self, *, text: bytes, fd: int, **kwargs: Unpack[ProcessDetails]) -> None:
        super().__init__(**kwargs)
        self.text = text
        self.from_stdout = fd == 1
        self.from_stderr = fd == 2


class ProcessStdout(ProcessIO):
    """A line the process wrote to stdout."""

    name = 'launch.events.process.ProcessStdout'

    def __init__(self, *, text: bytes, **kwargs: Unpack[ProcessDetails]) -> None:
        super().__init__(text=text, fd=1, **kwargs)


class ProcessStderr(ProcessIO):
    """A line the process wrote to stderr."""

    name = 'launch.events.process.ProcessStderr'

    def __init__(self, *, text: bytes, **kwargs: Unpack[ProcessDetails]) -> None:
        super().__init__(text=text, fd=2, **kwargs)


# picks processes by their action
ProcessMatcher = Callable[[ActionLike], bool]


def matches_action(target_action: ActionLike) -> ProcessMatcher:
    """A matcher that picks exactly `target_action`."""
    return lambda action: action is target_action


class ShutdownProcess(Event):
    """Asks matching processes to stop (SIGINT, then launch's escalation)."""

    name = 'launch.events.process.ShutdownProcess'

    def __init__(self, *, process_matcher: ProcessMatcher) -> None:
        self.process_matcher = process_matcher


class SignalProcess(Event):
    """Sends a signal to matching processes."""

    name = 'launch.events.process.SignalProcess'

    def __init__(self, *, signal_number: int | str, process_matcher: ProcessMatcher) -> None:
        if isinstance(signal_number, str):
            signal_number = int(getattr(_signal, signal_number))
        self.signal_number = int(signal_number)
        self.process_matcher = process_matcher

    @property
    def signal_name(self) -> str:
        """The signal's name (SIGINT, SIGTERM, …)."""
        return _signal.Signals(self.signal_number).name
