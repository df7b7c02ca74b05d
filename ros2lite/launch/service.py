"""LaunchService: runs launch descriptions until there is nothing left to do.

One thread (the caller's) does all the launch work: it visits entities, handles events,
fires timers and stops processes. Other threads only post to its queue — the readers of
each process' output (which also write the lines out at once), the process watchers, and
signal handlers (a :class:`queue.SimpleQueue` may be used from one).

Stopping follows launch: on Ctrl-C every process gets SIGINT, then SIGTERM after
``sigterm_timeout`` (5 s), then SIGKILL after ``sigkill_timeout`` (5 s) more; a second Ctrl-C
is ignored. Unlike launch, SIGTERM (or SIGQUIT) sent to the launch stops the processes the
same way instead of leaving them behind, and whatever a process started in its process
group is killed when the launch ends, so nothing it started stays running.
"""

from __future__ import annotations

import contextlib
import functools
import heapq
import itertools
import os
import queue
import signal
import threading
import time
import traceback
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import IO, TYPE_CHECKING, Literal, TypeVar

from ros2lite.util.process import ChildError, ChildProcess, signal_handler

from .actions import Entities, LaunchDescription, LaunchDescriptionEntity
from .context import EntityLike, LaunchContext, ProcessActionLike, Scope, TimerLike
from .event_handlers import OnProcessIO
from .events import (
    Event,
    ExecutionComplete,
    ProcessDetails,
    ProcessExited,
    ProcessStarted,
    ProcessStderr,
    ProcessStdout,
    Shutdown,
    ShutdownProcess,
    SignalProcess,
)
from .flow import TimerAction
from .output import LaunchOutput, Style, log_base_directory, make_log_directory
from .process_spec import ProcessSpec

if TYPE_CHECKING:
    from ros2lite.pkg.index import PackageIndex

__all__ = ['LaunchService']

_T = TypeVar('_T')
# what the loop is woken with: an event, a signal number, or (action id, exit code)
_Item = (
    tuple[Literal['event'], Event]
    | tuple[Literal['signal'], int]
    | tuple[Literal['exit'], int, int]
)

_SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGQUIT)


@dataclass
class _Running:
    action: ProcessActionLike
    spec: ProcessSpec
    label: str
    index: int
    child: ChildProcess
    pid: int


class LaunchService:
    """Runs the launch descriptions given to :meth:`include_launch_description`."""

    def __init__(
        self,
        *,
        argv: Sequence[str] = (),
        noninteractive: bool = False,
        debug: bool = False,
        style: Style | None = None,
        stream: IO[str] | None = None,
        log_dir: Path | None = None,
        write_logs: bool = True,
        output_override: str | None = None,
        index: PackageIndex | None = None,
    ) -> None:
        self.context = LaunchContext(argv=argv, noninteractive=noninteractive)
        if index is not None:
            self.context.use_package_index(index)
        self.context.service = self
        self.context.emit_event_sync = self.emit_event
        self.debug = debug
        self._style = style
        self._stream = stream
        self._log_dir = log_dir
        self._write_logs = write_logs
        self.output = LaunchOutput(stream=stream, style=style)
        self._queue: queue.SimpleQueue[_Item] = queue.SimpleQueue()
        self._descriptions: list[LaunchDescription] = []
        self._running: dict[int, _Running] = {}  # by id(action)
        self._started: list[ChildProcess] = []
        self._timers: list[tuple[float, int, TimerLike, dict[str, object], Scope]] = []
        self._seq = itertools.count()
        self._labels = itertools.count(1)
        self._shutting_down = False
        self._signals_seen = 0
        self._visiting = 0  # visits under way (reading launch files, running their code)
        self._stop_visiting = False  # a signal cut the visit under way short
        self._temp_files: list[str] = []
        self.return_code = 0
        # `launch -a`: every process' output to the screen too (else OVERRIDE_LAUNCH_PROCESS_OUTPUT)
        self.context.output_override = output_override
        # lines to log right after the log directory's (e.g. a stand-in package was used)
        self.pending_notes: list[str] = []

    # -- what callers and actions use -----------------------------------------------------------
    def include_launch_description(self, description: LaunchDescription) -> None:
        """Add a description to run when the service runs."""
        self._descriptions.append(description)

    def emit_event(self, event: Event) -> None:
        """Queue an event (any thread)."""
        self._queue.put(('event', event))

    def shutdown(self) -> None:
        """Ask the launch to stop (any thread)."""
        self._queue.put(('event', Shutdown(reason='LaunchService.shutdown() called')))

    def log(self, level: str, name: str, msg: str) -> None:
        """Write a launch log line (to the screen and the launch log)."""
        self.output.log(level, name, msg)

    @property
    def log_directory(self) -> Path | None:
        """Where this launch writes its logs (None when it writes none)."""
        return self.output.log_dir

    def add_timer(
        self, action: TimerLike, seconds: float, frame: dict[str, object], scope: Scope
    ) -> None:
        """Visit `action`'s actions in `seconds`, with these locals and in this scope."""
        due = time.monotonic() + seconds
        heapq.heappush(self._timers, (due, next(self._seq), action, frame, scope))

    def add_temp_file(self, path: str) -> None:
        """A file to delete when the launch ends (e.g. a generated parameter file)."""
        self._temp_files.append(path)

    def start_process(
        self, action: ProcessActionLike, spec: ProcessSpec, *, again: _Running | None = None
    ) -> None:
        """Start `action`'s process (ExecuteProcess.execute calls this); `again` is the run
        a respawn replaces (its label and colour are kept)."""
        if self._shutting_down:
            return
        label = again.label if again else f'{spec.name}-{next(self._labels)}'
        index = again.index if again else len(self._started)

        def on_line(stream: str, line: str) -> None:
            self.output.process_line(label, index, stream, line, spec.output[stream])
            if any(isinstance(h, OnProcessIO) for h in self.context.event_handlers):
                io = ProcessStdout if stream == 'stdout' else ProcessStderr
                self._queue.put(('event', io(text=(line + '\n').encode(), **details)))

        def on_exit(code: int) -> None:
            self._queue.put(('exit', id(action), code))

        child = ChildProcess(
            spec.cmd,
            env=spec.env,
            cwd=spec.cwd,
            on_line=on_line,
            on_exit=on_exit,
            sigterm_timeout=spec.sigterm_timeout,
            sigkill_timeout=spec.sigkill_timeout,
        )
        details: ProcessDetails = {
            'action': action,
            'name': label,
            'cmd': spec.display_cmd,
            'cwd': spec.cwd,
            'env': spec.env,
            'pid': 0,  # known once started
        }
        if spec.log_cmd:
            self.log(
                'INFO',
                label,
                f"process details: cmd='{' '.join(spec.display_cmd)}', cwd='{spec.cwd}', "
                f"custom_env?={action.env is not None}",
            )
        try:
            pid = child.start()
        except ChildError as e:
            self.log('ERROR', label, f'exception occurred while executing process: {e}')
            return
        details['pid'] = pid
        action.process_details = details
        self._started.append(child)
        self._running[id(action)] = _Running(action, spec, label, index, child, pid)
        self.log('INFO', label, f'process started with pid [{pid}]')
        self.emit_event(ProcessStarted(**details))

    # -- the loop --------------------------------------------------------------------------------
    def run(self, *, shutdown_when_idle: bool = True) -> int:
        """Run until idle (or shut down); returns 0, or 1 when the launch itself failed."""
        in_main = threading.current_thread() is threading.main_thread()
        signals = (
            signal_handler(self._on_signal_received, _SIGNALS)
            if in_main
            else contextlib.nullcontext()
        )
        with signals:
            # cleaning up inside the handlers: a late Ctrl-C cannot cut it short
            try:
                self._open_logs()
                for description in self._descriptions:
                    self._visit_guarded(description)
                self._loop(shutdown_when_idle)
            finally:
                self._cleanup()
        return self.return_code

    def _on_signal_received(self, signum: int) -> None:
        """The signal handler: the loop stops everything in order. A visit under way (a
        launch file being read or its code run, which may take long or never end) is cut
        short first, once, so the loop gets to it."""
        self._queue.put(('signal', signum))
        if self._visiting and not self._stop_visiting and self._signals_seen == 0:
            self._stop_visiting = True
            raise _Interrupted

    def _open_logs(self) -> None:
        if self._write_logs:
            try:
                directory = self._log_dir or make_log_directory(
                    log_base_directory(self.context.environment)
                )
            except OSError as e:
                self.log('WARNING', 'launch', f'no log files will be written: {e}')
            else:
                self.output.log_dir = directory
                self.log('INFO', 'launch', f'All log files can be found below {directory}')
        self.log('INFO', 'launch', 'Default logging verbosity is set to INFO')
        for note in self.pending_notes:
            self.log('INFO', 'launch', note)

    def _loop(self, shutdown_when_idle: bool) -> None:
        while True:
            now = time.monotonic()
            self._fire_timers(now)
            self._escalate(now)
            if self._idle():
                if self._shutting_down:
                    return
                if shutdown_when_idle:
                    self._begin_shutdown(Shutdown(reason='idle'))
                    continue
            try:
                item = self._queue.get(timeout=self._wait_time(time.monotonic()))
            except queue.Empty:
                continue
            self._handle(item)

    def _idle(self) -> bool:
        if not self._queue.empty() or self._running:
            return False
        pending = [t for t in self._timers if not t[2].cancelled]
        if self._shutting_down:
            pending = [t for t in pending if not t[2].cancel_on_shutdown]
        return not pending

    def _wait_time(self, now: float) -> float:
        deadlines = [t[0] for t in self._timers if not t[2].cancelled]
        deadlines += [
            d for r in self._running.values() if (d := r.child.next_deadline()) is not None
        ]
        if not deadlines:
            return 1.0
        return max(0.0, min(min(deadlines) - now, 1.0))

    def _handle(self, item: _Item) -> None:
        match item:
            case ('signal', signum):
                self._on_signal(signum)
            case ('exit', action_id, code):
                self._on_exit(action_id, code)
            case ('event', event):
                self._dispatch(event)

    def _on_signal(self, signum: int) -> None:
        self._signals_seen += 1
        self._stop_visiting = False  # (the visit it cut short has ended: shutdown visits)
        if signum == signal.SIGINT:
            message = 'user interrupted with ctrl-c (SIGINT)'
        else:
            message = f'received {signal.Signals(signum).name}, stopping every process'
        if self._signals_seen > 1 or self._shutting_down:
            self.log('WARNING', 'launch', f'{message} again, ignoring...')
            return
        self.log('WARNING', 'launch', message)
        reason = 'ctrl-c (SIGINT)' if signum == signal.SIGINT else signal.Signals(signum).name
        self._dispatch(Shutdown(reason=reason, due_to_sigint=signum == signal.SIGINT))

    # -- events ----------------------------------------------------------------------------------
    def _dispatch(self, event: Event) -> None:
        if isinstance(event, Shutdown):
            if self._shutting_down:
                return
            self._begin_shutdown(event)
            return
        self._run_handlers(event)
        if isinstance(event, ShutdownProcess):
            for running in list(self._running.values()):
                if event.process_matcher(running.action):
                    self._stop(running)
        elif isinstance(event, SignalProcess):
            for running in list(self._running.values()):
                if event.process_matcher(running.action):
                    self.log(
                        'INFO',
                        running.label,
                        f"sending signal '{event.signal_name}' to process[{running.label}]",
                    )
                    running.child.send_signal(event.signal_number)

    def _run_handlers(self, event: Event) -> None:
        for handler in list(self.context.handlers_for(event)):
            self.context.push_locals(handler.captured_locals)
            try:
                entities = self._guard(functools.partial(handler.handle, event, self.context))
                for entity in entities or []:
                    self._visit_guarded(entity)
            finally:
                self.context.pop_locals()

    def _begin_shutdown(self, event: Shutdown) -> None:
        self._shutting_down = True
        self.context.is_shutdown = True
        self._run_handlers(event)
        for timer in self._timers:
            if timer[2].cancel_on_shutdown:
                timer[2].cancel()
        for running in list(self._running.values()):
            self._stop(running)

    def _stop(self, running: _Running) -> None:
        if running.child.stopping:
            return
        self.log('INFO', running.label, f"sending signal 'SIGINT' to process[{running.label}]")
        running.child.begin_stop(time.monotonic())

    def _escalate(self, now: float) -> None:
        for running in list(self._running.values()):
            step = running.child.escalate(now)
            if step is not None:
                sent, after, seconds = step
                shown = f'{seconds:g}' if after == 'SIGINT' else f'{seconds:.1f}'
                self.log(
                    'ERROR',
                    running.label,
                    f"process[{running.label}] failed to terminate '{shown}' seconds after "
                    f"receiving '{after}', escalating to '{sent}'",
                )

    def _on_exit(self, key: int, code: int) -> None:
        running = self._running.pop(key, None)
        if running is None:
            return
        action = running.action
        action.return_code = code
        if code == 0:
            self.log('INFO', running.label, f'process has finished cleanly [pid {running.pid}]')
        else:
            cmd = ' '.join(part for part in running.spec.display_cmd if part.strip())
            self.log(
                'ERROR',
                running.label,
                f"process has died [pid {running.pid}, exit code {code}, cmd '{cmd}'].",
            )
        details = action.process_details
        assert details is not None  # set when the process started
        self._dispatch(ProcessExited(returncode=code, **details))
        self._dispatch(ExecutionComplete(action=action))
        if not self._shutting_down and self._guard(lambda: action.should_respawn(self.context)):
            action.respawn_count += 1
            self._respawn_later(running)

    def _respawn_later(self, previous: _Running) -> None:
        service = self
        action = previous.action

        class _Respawn(LaunchDescriptionEntity):
            def visit(self, context: LaunchContext) -> Entities | None:
                service.start_process(action, previous.spec, again=previous)
                return None

        timer = TimerAction(period=str(action.respawn_delay or 0.0), actions=[_Respawn()])
        delay = float(action.respawn_delay or 0.0)
        # the respawn reuses the process' spec: the scope it fires in does not matter
        self.add_timer(timer, delay, self.context.capture_locals(), self.context.scope.copy())

    def _fire_timers(self, now: float) -> None:
        while self._timers and self._timers[0][0] <= now:
            _deadline, _seq, timer, frame, scope = heapq.heappop(self._timers)
            if timer.cancelled:
                continue
            self.context.push_locals(frame)
            self.context.push_scope(saved=scope)  # what the actions set stays theirs
            try:
                for entity in timer.actions:
                    self._visit_guarded(entity)
            finally:
                self.context.pop_scope()
                self.context.pop_locals()

    # -- visiting --------------------------------------------------------------------------------
    def _visit_guarded(self, entity: EntityLike) -> None:
        """Visit depth first; an error stops the launch (as launch does) with one line, a
        signal stops the visit (the loop then stops the launch)."""
        stack: list[EntityLike] = [entity]
        self._visiting += 1
        try:
            while stack and not self._stop_visiting:
                current = stack.pop()
                result = self._guard(functools.partial(current.visit, self.context))
                if result is _FAILED:
                    return
                if result:
                    stack.extend(reversed(result))
        except _Interrupted:
            self.log('WARNING', 'launch', 'stopped reading the launch description')
        finally:
            self._visiting -= 1

    def _guard(self, fn: Callable[[], _T]) -> _T | _Failed:
        try:
            return fn()
        except Exception as e:
            message = str(e) or type(e).__name__
            if self.debug:
                message = traceback.format_exc().rstrip()
                self.log('ERROR', 'launch', f'Caught exception in launch:\n{message}')
            else:
                self.log(
                    'ERROR',
                    'launch',
                    f'Caught exception in launch (see debug for traceback): {message}',
                )
            self.return_code = 1
            if not self._shutting_down:
                self._begin_shutdown(Shutdown(reason='exception'))
            return _FAILED

    # -- the end ---------------------------------------------------------------------------------
    def _cleanup(self) -> None:
        # whatever still runs (an error in the loop itself) is killed, not left behind
        for running in list(self._running.values()):
            running.child.send_signal(signal.SIGKILL)
            running.child.wait(5.0)
        for child in self._started:
            child.kill_leftovers()
        for path in self._temp_files:
            with contextlib.suppress(OSError):
                os.unlink(path)
        self.output.close()


class _Interrupted(BaseException):
    """Raised by the signal handler into a visit under way (not an error of the launch)."""


class _Failed:
    def __bool__(self) -> Literal[False]:
        return False


_FAILED = _Failed()
