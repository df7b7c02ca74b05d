"""The launch library's errors: one line each, under ros2lite's error base."""

from __future__ import annotations

from ros2lite.exceptions import Ros2liteError

__all__ = [
    'InvalidConditionExpressionError',
    'InvalidFrontendLaunchFileError',
    'LaunchError',
    'SubstitutionFailure',
]


class LaunchError(Ros2liteError):
    """A launch description cannot be loaded or run; the message says why."""


class SubstitutionFailure(LaunchError):
    """A substitution has no value (an unset configuration or variable, a missing package)."""


class InvalidConditionExpressionError(LaunchError):
    """A condition's text is neither true nor false."""


class InvalidFrontendLaunchFileError(LaunchError):
    """An XML or YAML launch file that does not describe a launch."""
