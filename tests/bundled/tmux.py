"""A program in a tmux pane, as a person at a terminal sees it: keys sent, the screen read
back with `tmux capture-pane` (text, or with its colours as escape sequences)."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import uuid
from pathlib import Path

import pytest

from tests.spinning import wait_until


class TmuxPane:
    """`argv` alone in a detached tmux server of its own, `cols` x `rows`; the pane stays
    after the program ends, so its exit status can be read."""

    def __init__(
        self, argv: list[str], env: dict[str, str], tmp: Path, cols: int = 140, rows: int = 24
    ) -> None:
        if shutil.which('tmux') is None:
            pytest.skip('tmux is not installed: terminal tests need it (apt-get install tmux)')
        self.socket = f'ros2lite-test-{uuid.uuid4().hex[:12]}'
        conf = tmp / 'tmux.conf'
        conf.write_text('set -g remain-on-exit on\nset -g status off\n')
        env = {**env, 'TERM': 'xterm-256color'}
        env.pop('TMUX', None)
        self._tmux(
            '-f',
            str(conf),
            'new-session',
            '-d',
            '-x',
            str(cols),
            '-y',
            str(rows),
            '--',
            *argv,
            env=env,
        )
        self.server_pid = int(self._tmux('display-message', '-p', '#{pid}'))

    def _tmux(self, *args: str, env: dict[str, str] | None = None) -> str:
        return subprocess.run(
            ['tmux', '-L', self.socket, *args],
            capture_output=True,
            text=True,
            check=True,
            env=env if env is not None else dict(os.environ),
        ).stdout

    def screen(self, colours: bool = False) -> str:
        """What the pane shows now (with SGR colour sequences if `colours`)."""
        return self._tmux('capture-pane', '-p', *(['-e'] if colours else []))

    def title(self) -> str:
        """The pane's title (what an OSC 0 or 2 sequence from the program would set)."""
        return self._tmux('display-message', '-p', '#{pane_title}').strip()

    def history(self, lines: int = 200) -> str:
        """The screen with up to `lines` of scrollback above it (what scrolled off)."""
        return self._tmux('capture-pane', '-p', '-S', f'-{lines}')

    def wait_for(self, text: str, timeout: float = 20.0) -> str:
        """The screen once it shows `text`."""
        return str(wait_until(lambda: text in (s := self.screen()) and s, timeout))

    def resize(self, cols: int, rows: int) -> None:
        """Make the pane `cols` x `rows`, as a user dragging the terminal's corner."""
        self._tmux('resize-window', '-x', str(cols), '-y', str(rows))

    def keys(self, *keys: str) -> None:
        """Type `keys` (literal text, or tmux key names such as Enter)."""
        for key in keys:
            literal = key not in ('Enter', 'Escape', 'C-c')
            self._tmux('send-keys', *(['-l'] if literal else []), key)

    def exit_status(self, timeout: float = 30.0) -> int:
        """The program's exit status, once it has ended."""

        def status() -> str:
            # '1 <status>' once it ended (the status may lag a moment behind the '1')
            fields = self._tmux('list-panes', '-F', '#{pane_dead} #{pane_dead_status}').split()
            if fields[:1] == ['1'] and len(fields) > 1:
                return fields[1]
            # no status yet: the nudge is harmless when tmux lost nothing (a reap that finds
            # no child), and needed when it did, whether or not it has marked the pane dead
            self._reap()
            return ''

        return int(wait_until(status, timeout))

    def _reap(self) -> None:
        """Make the tmux server collect the exit status of a pane whose terminal closed.
        Built with libutempter (Debian's tmux 3.3a), it drops the SIGCHLD of a program that
        ends while the pane's utmp record is being removed, and then never reaps it: the pane
        stays dead without a status (tmux issue 4559; tmux 3.6 signals itself as we do)."""
        os.kill(self.server_pid, signal.SIGCHLD)

    def close(self) -> None:
        subprocess.run(['tmux', '-L', self.socket, 'kill-server'], capture_output=True)
