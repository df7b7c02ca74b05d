"""Supervised children (ros2lite.util.process.ChildProcess): output lines, exit, the stop
escalation and nothing left behind. (`run_child` is tested through `ros2lite run`.)"""

from __future__ import annotations

import os
import signal
import threading
import time
from pathlib import Path

import pytest

from ros2lite.util.process import ChildError, ChildProcess
from tests.spinning import wait_until


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    # a zombie counts as gone
    try:
        with open(f'/proc/{pid}/stat') as f:
            return f.read().split()[2] != 'Z'
    except OSError:
        return False


class Record:
    def __init__(self) -> None:
        self.lines: list[tuple[str, str]] = []
        self.codes: list[int] = []
        self.done = threading.Event()

    def line(self, stream: str, text: str) -> None:
        self.lines.append((stream, text))

    def exit(self, code: int) -> None:
        self.codes.append(code)
        self.done.set()


def test_lines_and_exit_status() -> None:
    rec = Record()
    child = ChildProcess(
        ['sh', '-c', 'echo out1; echo err1 >&2; printf "no newline"; exit 3'],
        on_line=rec.line,
        on_exit=rec.exit,
    )
    child.start()
    assert rec.done.wait(30)
    assert rec.codes == [3] and child.returncode == 3 and not child.running
    assert sorted(rec.lines) == [('stderr', 'err1'), ('stdout', 'no newline'), ('stdout', 'out1')]


def test_a_missing_command_is_one_clear_error() -> None:
    with pytest.raises(ChildError, match='no_such_program_here: No such file or directory'):
        ChildProcess(['no_such_program_here']).start()


def _group_alive(pgid: int) -> bool:
    try:
        os.killpg(pgid, 0)
    except ProcessLookupError:
        return False
    return True


def _group_runs(pgid: int, program: str) -> bool:
    """Whether a process of the group has exec'd `program` (not merely been forked for it)."""
    for entry in Path('/proc').iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / 'stat').read_text()
        except OSError:
            continue
        comm_end = stat.rindex(')')
        fields = stat[comm_end + 2 :].split()
        if stat[stat.index('(') + 1 : comm_end] == program and int(fields[2]) == pgid:
            return True
    return False


def test_sigint_reaches_the_whole_group() -> None:
    """A shell and the command it waits for both get the SIGINT (their own process group),
    so the group is empty once the shell has ended."""
    rec = Record()
    child = ChildProcess(
        ['sh', '-c', 'echo ready; sleep 60; echo not reached'],
        on_line=rec.line,
        on_exit=rec.exit,
    )
    pgid = child.start()
    wait_until(lambda: ('stdout', 'ready') in rec.lines, timeout=30)
    # a SIGINT in the moment between the shell's fork and the exec of sleep is taken by the
    # shell's own handler in the forked copy (dash catches SIGINT under -c), and sleep then
    # runs its full minute: that is the shell's race, so signal once sleep really runs
    wait_until(lambda: _group_runs(pgid, 'sleep'), timeout=30)
    assert child.begin_stop(time.monotonic()) is True
    assert rec.done.wait(30)
    assert ('stdout', 'not reached') not in rec.lines
    wait_until(lambda: not _group_alive(pgid), timeout=10)
    assert child.begin_stop(time.monotonic()) is False  # once, and only while running


def test_escalation_sigterm_then_sigkill() -> None:
    rec = Record()
    child = ChildProcess(
        ['sh', '-c', "trap '' INT TERM; echo ready; while :; do sleep 0.05; done"],
        on_line=rec.line,
        on_exit=rec.exit,
        sigterm_timeout=0.3,
        sigkill_timeout=0.3,
    )
    child.start()
    wait_until(lambda: ('stdout', 'ready') in rec.lines, timeout=30)
    # the clock is the caller's; this start once put start + 0.3 + 0.3 past start + 0.6
    start = 33144.698931567
    child.begin_stop(start)
    assert child.escalate(start) is None  # nothing is due yet
    assert child.next_deadline() == pytest.approx(start + 0.3)
    assert child.escalate(start + 0.3) == ('SIGTERM', 'SIGINT', 0.3)
    assert not rec.done.wait(0.5)  # SIGTERM is ignored too
    assert child.escalate(start + 0.6) == ('SIGKILL', 'SIGTERM', pytest.approx(0.6))
    assert rec.done.wait(30)
    assert rec.codes == [-signal.SIGKILL]
    assert child.next_deadline() is None


def test_leftovers_of_the_group_are_killed(tmp_path: Path) -> None:
    """A background job of a shell ignores SIGINT (POSIX): it goes when the launch ends."""
    pids = tmp_path / 'pids'
    rec = Record()
    child = ChildProcess(
        ['sh', '-c', f'sleep 60 > /dev/null 2>&1 & echo $! > {pids}'], on_exit=rec.exit
    )
    child.start()
    assert rec.done.wait(30) and rec.codes == [0]
    orphan = int(pids.read_text())
    assert _alive(orphan)
    child.kill_leftovers()
    wait_until(lambda: not _alive(orphan), timeout=10)
