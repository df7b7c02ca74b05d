"""Where a launch writes: the screen and the log directory, in launch's formats.

Screen lines go to stdout: launch's own messages as ``[INFO] [launch]: …`` and each line a
process writes as ``[talker-1] …``. The log directory is ``$ROS_LOG_DIR``, else
``$ROS_HOME/log``, else ``~/.ros/log``, plus ``<date-time>-<host>-<pid>/``; ``launch.log``
there gets every line with its time (``1714557601.1234567 [INFO] [launch]: …``), and
processes with ``output='own_log'`` get ``<name>-stdout.log`` / ``-stderr.log`` /
``-stdout_stderr.log``. A ``latest`` symlink points at the newest directory.

Colour is not decided here: a :class:`Style` passed in by the caller (the CLI, which knows
whether stdout is a terminal and honours ``NO_COLOR``) may decorate labels and levels.
"""

from __future__ import annotations

import contextlib
import datetime
import os
import socket
import sys
import threading
import time
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import IO, Protocol

__all__ = [
    'OUTPUT_MODES',
    'LaunchOutput',
    'PlainStyle',
    'Style',
    'destinations',
    'log_base_directory',
    'make_log_directory',
]

OUTPUT_MODES = ('screen', 'log', 'both', 'own_log', 'full')


class Style(Protocol):
    """How screen lines are decorated (colour on a terminal, nothing elsewhere)."""

    def label(self, text: str, index: int) -> str:
        """A process' `[name-N]` prefix; `index` picks its colour."""

    def level(self, text: str, level: str) -> str:
        """A whole launch log line of severity `level`."""


class PlainStyle:
    """No decoration: what scripts and files get."""

    def label(self, text: str, index: int) -> str:
        """The label as it is."""
        return text

    def level(self, text: str, level: str) -> str:
        """The line as it is."""
        return text


def destinations(mode: str) -> dict[str, set[str]]:
    """Where each stream of a process goes for an `output` mode, as launch defines them:
    {'stdout': {...}, 'stderr': {...}} with 'screen', 'log' (launch.log), 'own_log'."""
    table = {
        'screen': ({'screen'}, {'screen'}),
        'log': ({'log'}, {'log', 'screen'}),
        'both': ({'log', 'screen'}, {'log', 'screen'}),
        'own_log': ({'own_log'}, {'own_log'}),
        'full': ({'screen', 'log', 'own_log'}, {'screen', 'log', 'own_log'}),
    }
    if mode not in table:
        raise ValueError(
            f"'{mode}' is not a valid output mode: use one of {', '.join(OUTPUT_MODES)}"
        )
    out, err = table[mode]
    return {'stdout': out, 'stderr': err}


def log_base_directory(env: Mapping[str, str] | None = None) -> Path:
    """ROS_LOG_DIR, else ROS_HOME/log, else ~/.ros/log (as ROS tools agree)."""
    environ = os.environ if env is None else env
    if environ.get('ROS_LOG_DIR'):
        base = environ['ROS_LOG_DIR']
    else:
        base = os.path.join(environ.get('ROS_HOME') or os.path.join('~', '.ros'), 'log')
    return Path(os.path.normpath(os.path.expanduser(base)))


def make_log_directory(base: Path) -> Path:
    """A new, empty `<base>/<date-time>-<host>-<pid>` directory (created, never reused), and
    `<base>/latest` pointing at it when `latest` is ours to replace (absent or a symlink)."""
    base.mkdir(parents=True, exist_ok=True)
    while True:
        stamp = datetime.datetime.now().strftime('%Y-%m-%d-%H-%M-%S-%f')
        directory = base / f'{stamp}-{socket.gethostname()}-{os.getpid()}'
        try:
            directory.mkdir(mode=0o755)
        except FileExistsError:
            continue
        break
    latest = base / 'latest'
    with contextlib.suppress(OSError):
        if latest.is_symlink():
            latest.unlink()
        if not os.path.lexists(latest):
            latest.symlink_to(directory, target_is_directory=True)
    return directory


def _open_new(path: Path) -> IO[str]:
    """A log file in our own fresh directory: created here, never through a symlink."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_APPEND | getattr(os, 'O_NOFOLLOW', 0)
    return os.fdopen(os.open(path, flags, 0o644), 'a', encoding='utf-8', buffering=1)


class LaunchOutput:
    """The screen and the log files of one launch; safe to call from any thread."""

    def __init__(
        self,
        *,
        stream: IO[str] | None = None,
        style: Style | None = None,
        log_dir: Path | None = None,
    ) -> None:
        self.stream = stream
        self.style: Style = style if style is not None else PlainStyle()
        self.log_dir = log_dir
        self._lock = threading.Lock()
        self._files: dict[str, IO[str]] = {}
        self._broken: set[str] = set()

    def _screen(self, text: str) -> None:
        stream = self.stream if self.stream is not None else sys.stdout
        try:
            stream.write(text + '\n')
            stream.flush()
        except (OSError, ValueError):  # a closed or vanished terminal: keep launching
            pass

    def _file(self, name: str, text: str) -> None:
        if self.log_dir is None or name in self._broken:
            return
        handle = self._files.get(name)
        try:
            if handle is None:
                handle = self._files[name] = _open_new(self.log_dir / name)
            handle.write(text + '\n')
        except OSError:
            self._broken.add(name)

    def log(self, level: str, name: str, msg: str) -> None:
        """A launch message: `[LEVEL] [name]: msg` on screen and in launch.log."""
        line = f'[{level}] [{name}]: {msg}'
        with self._lock:
            for part in line.split('\n') if '\n' in msg else [line]:
                self._screen(self.style.level(part, level))
            self._file('launch.log', f'{time.time():.7f} {line}')

    def process_line(
        self, label: str, index: int, stream: str, line: str, where: Iterable[str]
    ) -> None:
        """One line of a process (`stream` 'stdout' or 'stderr') to where its output goes."""
        targets = set(where)
        with self._lock:
            if 'screen' in targets:
                self._screen(f'{self.style.label(f"[{label}]", index)} {line}')
            if 'log' in targets:
                self._file('launch.log', f'{time.time():.7f} [{label}] {line}')
            if 'own_log' in targets:
                self._file(f'{label}-{stream}.log', line)
                self._file(f'{label}-stdout_stderr.log', line)

    def close(self) -> None:
        """Close the launch log files."""
        with self._lock:
            for handle in self._files.values():
                with contextlib.suppress(OSError):
                    handle.close()
            self._files.clear()
