"""ProcessSpec: a process as its action resolved it, handed to the launch service to start.

It stands below both :mod:`.execute` (which makes it, and offers it too) and the launch
context (whose view of the service takes one), so neither has to import the other for it.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ['ProcessSpec']


@dataclass
class ProcessSpec:
    """A process as resolved when its action ran."""

    name: str  # the label without its number
    cmd: list[str]
    display_cmd: list[str]  # what messages show (a Python node's module, not `python -c …`)
    cwd: str | None
    env: dict[str, str]
    output: dict[str, set[str]]
    sigterm_timeout: float
    sigkill_timeout: float
    log_cmd: bool = False
