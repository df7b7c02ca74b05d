"""Errors of the type system, under ros2lite's one base.

Each also derives from the built-in it used to be, so ``except ValueError`` code still works.
"""

from __future__ import annotations

from collections.abc import Callable

from ros2lite.exceptions import Ros2liteError

__all__ = ['CdrError', 'FieldError', 'InterfaceError', 'PopulateError', 'UnknownInterfaceError']


class InterfaceError(Ros2liteError, ValueError):
    """A definition is broken; the message names the file, the line and the problem."""


class UnknownInterfaceError(InterfaceError, LookupError):
    """A package or type that no search path provides. `explain`, when given, says why
    (the package is in a workspace this process does not use, or not in ros2lite at all);
    it is asked once, when the message is shown, so code probing for types pays nothing."""

    def __init__(self, message: str, explain: Callable[[], str] | None = None) -> None:
        super().__init__(message)
        self._explain = explain
        self._text: str | None = None

    def __str__(self) -> str:
        if self._text is None:
            reason = self._explain() if self._explain is not None else ''
            self._text = str(self.args[0]) + (f'; {reason}' if reason else '')
        return self._text


class CdrError(Ros2liteError, ValueError):
    """Bytes that are not a valid CDR encoding of the expected type."""


class FieldError(Ros2liteError, TypeError, ValueError):
    """A value does not fit a field (wrong type, out of range, too long)."""


class PopulateError(Ros2liteError, ValueError):
    """Input values do not fit the message; str() is the reason ros2cli would print."""
