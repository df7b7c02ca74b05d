"""Errors of the type system, under ros2lite's one base.

Each also derives from the built-in it used to be, so ``except ValueError`` code still works.
"""

from __future__ import annotations

from ros2lite.exceptions import Ros2liteError

__all__ = ['CdrError', 'FieldError', 'InterfaceError', 'PopulateError', 'UnknownInterfaceError']


class InterfaceError(Ros2liteError, ValueError):
    """A definition is broken; the message names the file, the line and the problem."""


class UnknownInterfaceError(InterfaceError, LookupError):
    """A package or type that no search path provides."""


class CdrError(Ros2liteError, ValueError):
    """Bytes that are not a valid CDR encoding of the expected type."""


class FieldError(Ros2liteError, TypeError, ValueError):
    """A value does not fit a field (wrong type, out of range, too long)."""


class PopulateError(Ros2liteError, ValueError):
    """Input values do not fit the message; str() is the reason ros2cli would print."""
