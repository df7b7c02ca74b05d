"""Conditions: whether an action runs, decided when it is reached."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from .substitutions import (
    SomeSubstitutionsType,
    describe_substitutions,
    evaluate_condition_expression,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

if TYPE_CHECKING:
    from .context import LaunchContext

__all__ = [
    'Condition',
    'IfCondition',
    'LaunchConfigurationEquals',
    'LaunchConfigurationNotEquals',
    'UnlessCondition',
    'evaluate_condition_expression',
]


class Condition:
    """A predicate over the launch context."""

    def __init__(self, *, predicate: Callable[[LaunchContext], bool] | None = None) -> None:
        self._predicate = predicate

    def evaluate(self, context: LaunchContext) -> bool:
        """Whether the guarded action runs, in this context."""
        return bool(self._predicate(context)) if self._predicate is not None else True

    def describe(self) -> str:
        """A short description for introspection."""
        return type(self).__name__


class IfCondition(Condition):
    """True when the expression performs to 'true' or '1'."""

    def __init__(self, predicate_expression: SomeSubstitutionsType) -> None:
        super().__init__()
        self.expression = normalize_to_list_of_substitutions(predicate_expression)

    def evaluate(self, context: LaunchContext) -> bool:
        """True when the expression performs to 'true' or '1'."""
        return evaluate_condition_expression(context, self.expression)

    def describe(self) -> str:
        """The expression, for introspection."""
        return f'IfCondition({describe_substitutions(self.expression)})'


class UnlessCondition(IfCondition):
    """True when the expression performs to 'false' or '0'."""

    def evaluate(self, context: LaunchContext) -> bool:
        """True when the expression performs to 'false' or '0'."""
        return not evaluate_condition_expression(context, self.expression)

    def describe(self) -> str:
        """The expression, for introspection."""
        return f'UnlessCondition({describe_substitutions(self.expression)})'


class LaunchConfigurationEquals(Condition):
    """True when a launch configuration equals a value (None: when it is not set)."""

    def __init__(
        self, launch_configuration_name: str, expected_value: SomeSubstitutionsType | None
    ) -> None:
        super().__init__()
        self.name = launch_configuration_name
        self.expected = (
            None if expected_value is None else normalize_to_list_of_substitutions(expected_value)
        )

    def _equal(self, context: LaunchContext) -> bool:
        value = context.launch_configurations.get(self.name)
        if self.expected is None:
            return value is None
        return value == perform_substitutions(context, self.expected)

    def evaluate(self, context: LaunchContext) -> bool:
        """True when the configuration's value equals the expected one."""
        return self._equal(context)


class LaunchConfigurationNotEquals(LaunchConfigurationEquals):
    """True when a launch configuration differs from a value."""

    def evaluate(self, context: LaunchContext) -> bool:
        """True when the configuration's value differs from the expected one."""
        return not self._equal(context)
