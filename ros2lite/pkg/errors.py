"""The package index's errors: one class for a package nobody knows, one for a package file
that cannot be read, one for a package ros2lite does not provide.

Every verb and face that looks a package up raises these same classes (`run`, `launch`,
`pkg`, `ament_index_python`, launch's `FindPackageShare`), so one ``except`` catches them all
and each message is written in one place.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path

from ros2lite.exceptions import Ros2liteError

__all__ = ['NotHereError', 'PackageFileError', 'PackageNotFoundError', 'did_you_mean']


class PackageNotFoundError(Ros2liteError, KeyError):
    """No source knows the package. A KeyError (so a LookupError) as ament_index_python's
    is, which code written for ROS catches. The message names close matches or, when
    `explain` (asked once, only when the message is shown: code that catches the error pays
    no search) says why, that reason instead."""

    def __init__(
        self,
        package: str,
        known: Sequence[str] = (),
        *,
        message: str | None = None,
        explain: Callable[[], str] | None = None,
    ) -> None:
        super().__init__(message if message is not None else f"Package '{package}' not found")
        self.package = package
        self._known = tuple(known)
        self._explain = explain
        self._text: str | None = None

    def __str__(self) -> str:  # KeyError's own would quote the message
        if self._text is None:
            reason = self._explain() if self._explain is not None else ''
            tail = f'; {reason}' if reason else did_you_mean(self.package, self._known)
            self._text = str(self.args[0]) + tail
        return self._text


class PackageFileError(Ros2liteError, ValueError):
    """A package's own file (package.xml, setup.py, setup.cfg, a .msg) that cannot be read:
    one line, `file:line: what is wrong`, as colcon names it."""

    def __init__(self, path: Path, line: int | None, problem: str, package: str = '') -> None:
        where = f'{path}:{line}' if line else str(path)
        super().__init__(f'{where}: {problem}')
        self.path = path
        self.line = line
        self.problem = problem
        self.package = package or path.parent.name


class NotHereError(PackageNotFoundError):
    """A package ros2lite does not provide or cannot run (C++ code, Gazebo, rviz2): what is
    missing and what to use instead, in one line. Still a PackageNotFoundError, so code
    written for ROS that catches that (a launch file probing for gazebo_ros) goes on."""

    def __init__(self, package: str, message: str) -> None:
        super().__init__(package, message=message)


def did_you_mean(name: str, candidates: Sequence[str]) -> str:
    """'; did you mean: a, b?' for the close matches of `name`, or ''."""
    import difflib  # only when a message is shown; the index loads this module everywhere

    close = difflib.get_close_matches(name, sorted(set(candidates)), n=3, cutoff=0.6)
    return f"; did you mean: {', '.join(close)}?" if close else ''
