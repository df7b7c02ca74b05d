"""Child processes and stop signals, for `run` and `launch`.

Signals are a process-wide resource, so everything that installs a handler does it here,
for a bounded stretch of code (a ``with`` block or one call), and puts back what was there.
Ctrl-C typed in a terminal reaches a child by itself (same foreground process group), so it
is forwarded only when it did not come from the terminal (``kill -INT``, a test, a
supervisor) or when it is the second one; SIGTERM is always forwarded.

That is :func:`run_child`, one child that shares our terminal. :class:`ChildProcess` is for
a supervisor of many (`launch`): each child gets a process group of its own and its output
through pipes, and the supervisor stops them itself with launch's escalation.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
from collections.abc import Callable, Iterator, Mapping, Sequence
from types import FrameType
from typing import IO, TYPE_CHECKING, Any

from ros2lite.exceptions import Ros2liteError

if TYPE_CHECKING:  # loaded by what spawns: every CLI call imports this module for its signals
    import subprocess

__all__ = [
    'SIGKILL_TIMEOUT',
    'SIGTERM_TIMEOUT',
    'ChildError',
    'ChildProcess',
    'StopSignals',
    'Terminated',
    'exit_code',
    'forget_caught_interrupt',
    'ignore_hangup',
    'release_interrupts',
    'run_child',
    'signal_handler',
    'stop_signals_raise',
    'switch_interval',
    'terminal_signals_child',
]

_Handler = Callable[[int, FrameType | None], object] | int | signal.Handlers | None


class ChildError(Ros2liteError, OSError):
    """A child process could not be started; the message names the command and why."""


class Terminated(BaseException):
    """SIGTERM, raised where the main thread is, so ``with`` blocks close sessions on the
    way out (a BaseException: nothing that catches ``Exception`` swallows it)."""


def _in_main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


@contextlib.contextmanager
def _handlers(handlers: dict[int, _Handler]) -> Iterator[None]:
    """Install `handlers` for the block (main thread only; elsewhere a no-op)."""
    if not _in_main_thread():
        yield
        return
    previous = {sig: signal.signal(sig, handler) for sig, handler in handlers.items()}
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler if handler is not None else signal.SIG_DFL)


@contextlib.contextmanager
def on_signals(callbacks: dict[int, Callable[[], object]]) -> Iterator[None]:
    """Within the block, each signal of `callbacks` runs its callback (in the main thread,
    between two of its steps; elsewhere the block changes nothing): SIGUSR1 asking a
    snapshot recorder to write, say."""

    def handler_for(callback: Callable[[], object]) -> _Handler:
        def handle(_signum: int, _frame: FrameType | None) -> None:
            callback()

        return handle

    with _handlers({sig: handler_for(cb) for sig, cb in callbacks.items()}):
        yield


@contextlib.contextmanager
def stop_signals_raise() -> Iterator[None]:
    """Within the block, SIGTERM raises :class:`Terminated` and SIGINT KeyboardInterrupt in the
    main thread, SIGINT even when it came ignored: a shell script's background job starts with
    SIGINT ignored, and ros2cli (rclpy takes SIGINT whatever it inherited) still stops on it."""

    def raise_terminated(_signum: int, _frame: FrameType | None) -> None:
        raise Terminated()

    handlers: dict[int, _Handler] = {signal.SIGTERM: raise_terminated}
    if signal.getsignal(signal.SIGINT) == signal.SIG_IGN:
        handlers[signal.SIGINT] = signal.default_int_handler
    with _handlers(handlers):
        yield


class StopSignals:
    """SIGINT and SIGTERM only set :attr:`event` inside the block: a long job (recording a
    bag) finishes cleanly instead of being cut short by a second Ctrl-C. `on_stop()` also
    runs (in the main thread, between two of its steps) for work that polls no event."""

    def __init__(self, on_stop: Callable[[], object] | None = None) -> None:
        self.event = threading.Event()
        self._on_stop = on_stop
        self._block: contextlib.ExitStack | None = None

    def _handle(self, _signum: int, _frame: FrameType | None) -> None:
        self.event.set()
        if self._on_stop is not None:
            self._on_stop()

    def __enter__(self) -> StopSignals:
        self._block = contextlib.ExitStack()
        self._block.enter_context(
            _handlers({signal.SIGINT: self._handle, signal.SIGTERM: self._handle})
        )
        return self

    def __exit__(self, *exc: object) -> None:
        if self._block is not None:
            self._block.close()
            self._block = None


def _has_terminal() -> bool:
    """Whether this process has a controlling terminal."""
    try:
        fd = os.open('/dev/tty', os.O_RDONLY | os.O_NOCTTY)
    except OSError:
        return False
    os.close(fd)
    return True


def terminal_signals_child() -> bool:
    """True when we run in the foreground of a terminal, where Ctrl-C hits the whole process
    group — the child included — so forwarding it would deliver it twice."""
    try:
        fd = os.open('/dev/tty', os.O_RDONLY | os.O_NOCTTY)
    except OSError:
        return False
    try:
        return os.tcgetpgrp(fd) == os.getpgrp()
    except OSError:
        return False
    finally:
        os.close(fd)


def die_with_us() -> Callable[[], None] | None:
    """What a child runs between fork and exec so that it gets SIGTERM when this process
    dies, even by SIGKILL (Linux's PR_SET_PDEATHSIG; None elsewhere): a node must not run on
    orphaned after its `run` or `launch` is gone. SIGTERM, not SIGKILL, lets it end cleanly.

    The request holds for the thread that starts the child (its exit counts as the parent's
    death): children are started by the thread that also stops them."""
    if not sys.platform.startswith('linux'):
        return None
    import ctypes

    try:
        prctl = ctypes.CDLL(None, use_errno=True).prctl  # resolved before the fork
    except (OSError, AttributeError):
        return None
    parent = os.getpid()

    def arm() -> None:
        prctl(1, int(signal.SIGTERM), 0, 0, 0)  # PR_SET_PDEATHSIG
        if os.getppid() != parent:  # we died before the request took hold
            os.kill(os.getpid(), signal.SIGTERM)

    return arm


def run_child(
    cmd: Sequence[str],
    on_start: Callable[[subprocess.Popen[bytes]], object] | None = None,
    env: Mapping[str, str] | None = None,
    *,
    hold_interrupts: bool = False,
) -> int:
    """Start `cmd` (in `env`, default this process's environment), forward SIGINT/SIGTERM to
    it (see the module doc), return its returncode (negative: killed by that signal).
    `on_start(child)` runs once the child is started, with the forwarding in place
    (`component standalone` loads its component there); if it raises, the child is
    interrupted and waited for before the error goes on.

    Signals are taken by handlers installed before the child starts, not as
    KeyboardInterrupt: a Ctrl-C landing between the child's start and our wait would
    otherwise end this process early, and the terminal would hang up on the child.

    `hold_interrupts`: the child starts with SIGINT blocked and unblocks it itself with
    :func:`release_interrupts` (`ros2lite.pkg.runner` does, first thing): a Ctrl-C during
    its interpreter's start-up then waits for it instead of landing in `site`, which
    prints it and carries on (a node that then never stops) or dies with a traceback.
    """
    proc: subprocess.Popen[bytes] | None = None
    interrupts = 0
    terminated = False
    # Without a terminal the child gets a process group of its own: a signal sent to our
    # group (a supervisor, `kill -INT -PGID`) then reaches it once, through us, not a second
    # time as we forward it — a second Ctrl-C landing in its clean-up (`destroy_node()` after
    # `except KeyboardInterrupt`) would end it with a traceback. With one, the child stays in
    # our group, the shell's job, so `fg` gives it the terminal too.
    own_group = not _has_terminal()

    def forward_int(_signum: int, _frame: FrameType | None) -> None:
        nonlocal interrupts
        interrupts += 1
        if (
            proc is not None
            and proc.poll() is None
            and (interrupts > 1 or own_group or not terminal_signals_child())
        ):
            proc.send_signal(signal.SIGINT)

    def forward_term(signum: int, _frame: FrameType | None) -> None:
        nonlocal terminated
        terminated = True
        if proc is not None and proc.poll() is None:
            proc.send_signal(signum)

    import subprocess

    with _handlers({signal.SIGINT: forward_int, signal.SIGTERM: forward_term}):
        try:
            try:
                with _blocked(signal.SIGINT) if hold_interrupts else contextlib.nullcontext():
                    proc = subprocess.Popen(
                        list(cmd),
                        env=None if env is None else dict(env),
                        **_child_options(own_group),
                    )
            except OSError as e:
                raise ChildError(f'{cmd[0]}: {e.strerror or e}') from None
            # signals that came while the child was starting (it may already run and be
            # seen running, so a SIGTERM then is no rarer than one later)
            if terminated:
                proc.send_signal(signal.SIGTERM)
            elif interrupts and (own_group or not terminal_signals_child()):
                proc.send_signal(signal.SIGINT)
            if on_start is not None:
                try:
                    on_start(proc)
                except BaseException:
                    if proc.poll() is None:
                        proc.send_signal(signal.SIGINT)
                    proc.wait()
                    raise
            return proc.wait()
        finally:
            sys.stdout.flush()


@contextlib.contextmanager
def _blocked(sig: int) -> Iterator[None]:
    """`sig` blocked in this thread for the block (a child started meanwhile inherits the
    mask); one that came meanwhile is delivered, to our handler, as the block ends."""
    signal.pthread_sigmask(signal.SIG_BLOCK, {sig})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {sig})


def release_interrupts() -> None:
    """Unblock SIGINT, which `run_child(hold_interrupts=True)` started us with blocked; a
    Ctrl-C that came during start-up arrives now (KeyboardInterrupt, as ever)."""
    if _in_main_thread():
        signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


def _child_options(own_group: bool) -> dict[str, Any]:
    """Popen's arguments for a child that dies with us (:func:`die_with_us`) and, when asked,
    has a process group of its own."""
    arm = die_with_us()
    if not own_group:
        return {'preexec_fn': arm}
    if sys.version_info >= (3, 11):
        return {'process_group': 0, 'preexec_fn': arm}

    def own_group_and_arm() -> None:  # pragma: no cover - Python 3.10
        os.setpgrp()
        if arm is not None:
            arm()

    return {'preexec_fn': own_group_and_arm}


def forget_caught_interrupt() -> None:
    """Let a `python -m` program that caught Ctrl-C leave with the status it chose.

    CPython remembers a KeyboardInterrupt that escaped an ``exec()`` of source text (which
    dataclasses, namedtuples and generated codecs do as they are made) even when the program
    caught it further out, and `-m` start-up then ends the process by SIGINT instead of with
    the program's status. An ``exec()`` that completes clears that memory; call this just
    before leaving.
    """
    exec('')


def exit_code(returncode: int) -> int:
    """A shell's exit status for a child's returncode (killed by signal N → 128 + N)."""
    return 128 - returncode if returncode < 0 else returncode


@contextlib.contextmanager
def switch_interval(seconds: float) -> Iterator[None]:
    """This process' thread switch interval at most `seconds` within the block: for the
    process' owner (e.g. `bag play`) when one thread must run on time while others work,
    never for a library object on its own."""
    previous = sys.getswitchinterval()
    sys.setswitchinterval(min(previous, seconds))
    try:
        yield
    finally:
        sys.setswitchinterval(previous)


# -- supervised children (launch) -----------------------------------------------------------------

SIGTERM_TIMEOUT = 5.0  # launch's defaults: SIGINT, then SIGTERM 5 s later, SIGKILL 5 s after that
SIGKILL_TIMEOUT = 5.0

LineCallback = Callable[[str, str], None]  # (stream 'stdout'|'stderr', line without newline)
ExitCallback = Callable[[int], None]


def ignore_hangup() -> None:
    """From now on SIGHUP is ignored: a daemon outlives the terminal that started it."""
    signal.signal(signal.SIGHUP, signal.SIG_IGN)


@contextlib.contextmanager
def signal_handler(handler: Callable[[int], None], signals: Sequence[int]) -> Iterator[None]:
    """Within the block, `signals` only call `handler(signum)` (main thread; elsewhere a
    no-op). The handler runs between two bytecodes of the main thread: it must only post
    work somewhere (a :class:`queue.SimpleQueue` is safe for that), never block."""

    def call(signum: int, _frame: FrameType | None) -> None:
        handler(signum)

    with _handlers(dict.fromkeys(signals, call)):
        yield


class ChildProcess:
    """A child in a process group of its own, its output read line by line on threads.

    Its own group means a signal from us reaches everything it started (a shell's children
    too), and a Ctrl-C typed at the terminal reaches only our process, which then stops the
    children in order — each gets exactly one SIGINT. Stopping escalates as launch does:
    SIGINT, SIGTERM after `sigterm_timeout`, SIGKILL after `sigkill_timeout` more
    (:meth:`begin_stop`, then :meth:`escalate` whenever :meth:`next_deadline` passes).
    """

    def __init__(
        self,
        cmd: Sequence[str],
        *,
        env: Mapping[str, str] | None = None,
        cwd: str | None = None,
        on_line: LineCallback | None = None,
        on_exit: ExitCallback | None = None,
        sigterm_timeout: float = SIGTERM_TIMEOUT,
        sigkill_timeout: float = SIGKILL_TIMEOUT,
    ) -> None:
        self.cmd = list(cmd)
        self.env = None if env is None else dict(env)
        self.cwd = cwd
        self.on_line = on_line
        self.on_exit = on_exit
        self.sigterm_timeout = sigterm_timeout
        self.sigkill_timeout = sigkill_timeout
        self._proc: subprocess.Popen[bytes] | None = None
        self._readers: list[threading.Thread] = []
        self._exited = threading.Event()
        self._stop_started: float | None = None
        self._stage = 0  # signals sent while stopping: 1 SIGINT (or skipped), 2 SIGTERM, 3 SIGKILL

    # -- life ------------------------------------------------------------------------------------
    def start(self) -> int:
        """Start it; returns the pid. Raises :class:`ChildError` when it cannot start."""
        import subprocess

        try:
            self._proc = subprocess.Popen(
                self.cmd,
                env=self.env,
                cwd=self.cwd,
                stdin=subprocess.DEVNULL,
                stdout=subprocess.PIPE,
                stderr=subprocess.PIPE,
                start_new_session=True,
                preexec_fn=die_with_us(),
            )
        except OSError as e:
            raise ChildError(f'{self.cmd[0]}: {e.strerror or e}') from None
        assert self._proc.stdout is not None and self._proc.stderr is not None
        for name, stream in (('stdout', self._proc.stdout), ('stderr', self._proc.stderr)):
            t = threading.Thread(
                target=self._read, args=(name, stream), name=f'child-{name}', daemon=True
            )
            t.start()
            self._readers.append(t)
        threading.Thread(target=self._wait, name='child-wait', daemon=True).start()
        return self._proc.pid

    def _read(self, name: str, stream: IO[bytes]) -> None:
        try:
            for raw in iter(stream.readline, b''):
                if self.on_line is not None:
                    self.on_line(name, raw.decode('utf-8', 'replace').rstrip('\r\n'))
        except (OSError, ValueError):
            pass
        finally:
            with contextlib.suppress(OSError):
                stream.close()

    def _wait(self) -> None:
        assert self._proc is not None
        code = self._proc.wait()
        # deliver its last lines before saying it ended (a grandchild may hold the pipes
        # open for longer: then only a short wait)
        for t in self._readers:
            t.join(timeout=1.0)
        self._exited.set()
        if self.on_exit is not None:
            self.on_exit(code)

    @property
    def pid(self) -> int | None:
        return self._proc.pid if self._proc is not None else None

    @property
    def returncode(self) -> int | None:
        """Its exit status once it has ended and been reaped (negative: killed by a signal)."""
        return self._proc.returncode if self._proc is not None else None

    @property
    def running(self) -> bool:
        return self._proc is not None and not self._exited.is_set()

    def wait(self, timeout: float | None = None) -> bool:
        """Wait until it has ended and its output was delivered; True if it has."""
        return self._exited.wait(timeout)

    # -- signals ---------------------------------------------------------------------------------
    def send_signal(self, sig: int) -> bool:
        """Signal its whole process group; False when it has already ended."""
        proc = self._proc
        if proc is None or proc.poll() is not None:
            return False
        try:
            os.killpg(proc.pid, sig)
        except ProcessLookupError:
            return False
        return True

    def begin_stop(self, now: float, *, send_sigint: bool = True) -> bool:
        """Start stopping it (once): SIGINT now unless told not to, the rest by
        :meth:`escalate`. Returns whether a SIGINT was sent."""
        if self._stop_started is not None or not self.running:
            return False
        self._stop_started = now
        self._stage = 1
        return self.send_signal(signal.SIGINT) if send_sigint else False

    @property
    def stopping(self) -> bool:
        return self._stop_started is not None

    def next_deadline(self) -> float | None:
        """When :meth:`escalate` has its next step to take (None: nothing pending)."""
        if self._stop_started is None or not self.running or self._stage >= 3:
            return None
        if self._stage == 1:
            return self._stop_started + self.sigterm_timeout
        # one sum of the timeouts, as escalate() reports it: (start + a) + b can land a
        # rounding step past start + (a + b)
        return self._stop_started + (self.sigterm_timeout + self.sigkill_timeout)

    def escalate(self, now: float) -> tuple[str, str, float] | None:
        """Take the step that is due, if any: (signal sent, signal it follows, seconds since
        the stop began as launch counts them) — e.g. ('SIGTERM', 'SIGINT', 5.0)."""
        deadline = self.next_deadline()
        if deadline is None or now < deadline:
            return None
        if self._stage == 1:
            self._stage = 2
            self.send_signal(signal.SIGTERM)
            return 'SIGTERM', 'SIGINT', self.sigterm_timeout
        self._stage = 3
        self.send_signal(signal.SIGKILL)
        return 'SIGKILL', 'SIGTERM', self.sigterm_timeout + self.sigkill_timeout

    def kill_leftovers(self) -> None:
        """SIGKILL whatever is left of its process group once it has ended (e.g. a
        background job of a shell it ran), so nothing it started outlives the launch."""
        proc = self._proc
        if proc is None or proc.poll() is None:
            return
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(proc.pid, signal.SIGKILL)
