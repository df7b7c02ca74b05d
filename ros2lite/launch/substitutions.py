"""Substitutions: values of a launch description that are known only while it runs.

A substitution is performed against the :class:`~ros2lite.launch.context.LaunchContext` and
yields a string. Anywhere a launch action takes text it accepts a *some-substitutions* value:
a string, one substitution, or a list mixing both (joined without separators), as launch
does. :func:`normalize_to_list_of_substitutions` and :func:`perform_substitutions` are the
two helpers every action uses.
"""

from __future__ import annotations

import math
import os
import secrets
import shlex
import shutil
import subprocess
from collections.abc import Iterable, Mapping, Sequence
from typing import TYPE_CHECKING, TypeAlias

from ros2lite.pkg.environment import child_environment

from .errors import InvalidConditionExpressionError, SubstitutionFailure

if TYPE_CHECKING:
    from .context import LaunchContext

__all__ = [
    'AndSubstitution',
    'AnonName',
    'Command',
    'EnvironmentVariable',
    'EqualsSubstitution',
    'FindExecutable',
    'IfElseSubstitution',
    'LaunchConfiguration',
    'LocalSubstitution',
    'NotEqualsSubstitution',
    'NotSubstitution',
    'OrSubstitution',
    'PathJoinSubstitution',
    'PythonExpression',
    'SomeSubstitutionsType',
    'Substitution',
    'SubstitutionFailure',
    'TextSubstitution',
    'ThisLaunchFile',
    'ThisLaunchFileDir',
    'evaluate_condition_expression',
    'normalize_to_list_of_substitutions',
    'perform_substitutions',
]


class Substitution:
    """Something that becomes text when the launch runs."""

    def perform(self, context: LaunchContext) -> str:
        """The text, in this context."""
        raise NotImplementedError

    def describe(self) -> str:
        """A short human description (used by `launch -s` and `-p`)."""
        return type(self).__name__ + '(...)'

    def __repr__(self) -> str:
        return self.describe()


SomeSubstitutionsType: TypeAlias = 'str | Substitution | Iterable[str | Substitution]'
# (key, value) settings given as a dict: names and values are text or substitutions
SubstitutionMapping: TypeAlias = (
    'Mapping[str, SomeSubstitutionsType] | Mapping[Substitution, SomeSubstitutionsType]'
)


def _one(value: object) -> Substitution | None:
    if isinstance(value, Substitution):
        return value
    if isinstance(value, bool):
        return TextSubstitution(text=str(value).lower())
    if isinstance(value, (str, int, float)):
        return TextSubstitution(text=str(value))
    if isinstance(value, os.PathLike):
        return TextSubstitution(text=os.fspath(value))
    return None


def normalize_to_list_of_substitutions(value: object) -> list[Substitution]:
    """A list of substitutions from a string, a substitution or a list of both."""
    single = _one(value)
    if single is not None:
        return [single]
    if isinstance(value, Iterable):
        out: list[Substitution] = []
        for item in value:
            sub = _one(item)
            if sub is None:
                raise TypeError(f'expected text or substitutions, got {type(item).__name__}')
            out.append(sub)
        return out
    raise TypeError(f'expected text or substitutions, got {type(value).__name__}')


def perform_substitutions(context: LaunchContext, subs: Sequence[Substitution]) -> str:
    """The text of a list of substitutions, concatenated."""
    return ''.join(context.perform_substitution(s) for s in subs)


def describe_substitutions(subs: Sequence[Substitution]) -> str:
    """Substitutions described and joined with ' + ' (for `launch -s` and `-p`)."""
    return ' + '.join(s.describe() for s in subs)


# -- plain values --------------------------------------------------------------------------------


class TextSubstitution(Substitution):
    """Literal text."""

    def __init__(self, *, text: str) -> None:
        self.text = str(text)

    def perform(self, context: LaunchContext) -> str:
        """The text as given."""
        return self.text

    def describe(self) -> str:
        """The text, quoted."""
        return repr(self.text)


class LaunchConfiguration(Substitution):
    """The value of a launch configuration (an argument, or what SetLaunchConfiguration set),
    or `default` when it is not set."""

    def __init__(self, variable_name: SomeSubstitutionsType, *, default: object = None) -> None:
        self.variable_name = normalize_to_list_of_substitutions(variable_name)
        self.default = None if default is None else normalize_to_list_of_substitutions(default)

    def perform(self, context: LaunchContext) -> str:
        """The configuration's value, else the default; a failure when neither exists."""
        name = perform_substitutions(context, self.variable_name)
        value = context.launch_configurations.get(name)
        if value is not None:
            return str(value)
        if self.default is not None:
            return perform_substitutions(context, self.default)
        raise SubstitutionFailure(f"launch configuration '{name}' does not exist")

    def describe(self) -> str:
        """The configuration's name, as launch shows it."""
        return f'LaunchConfig({describe_substitutions(self.variable_name)})'


class LocalSubstitution(Substitution):
    """A value from the context's locals (e.g. 'event.returncode' inside an event handler)."""

    def __init__(self, expression: str, description: str | None = None) -> None:
        self.expression = expression
        self.description = description

    def perform(self, context: LaunchContext) -> str:
        """The dotted local (`event.returncode`) as text; a failure when it is not set."""
        value: object = context.get_locals_as_dict()
        for part in self.expression.split('.'):
            value = value[part] if isinstance(value, dict) else getattr(value, part, None)
            if value is None:
                raise SubstitutionFailure(f"local '{self.expression}' is not set")
        return str(value)

    def describe(self) -> str:
        """The given description, or the expression."""
        return self.description or f'LocalVar({self.expression!r})'


class EnvironmentVariable(Substitution):
    """An environment variable of the launch (which SetEnvironmentVariable can change)."""

    def __init__(self, name: SomeSubstitutionsType, *, default_value: object = None) -> None:
        self.name = normalize_to_list_of_substitutions(name)
        self.default_value = (
            None if default_value is None else normalize_to_list_of_substitutions(default_value)
        )

    def perform(self, context: LaunchContext) -> str:
        """The variable's value, else the default; a failure when neither exists."""
        name = perform_substitutions(context, self.name)
        value = context.environment.get(name)
        if value is not None:
            return value
        if self.default_value is not None:
            return perform_substitutions(context, self.default_value)
        raise SubstitutionFailure(f"environment variable '{name}' does not exist")

    def describe(self) -> str:
        """The variable's name, as launch shows it."""
        return f'EnvVar({describe_substitutions(self.name)})'


class PathJoinSubstitution(Substitution):
    """Path parts joined with the platform's separator; `a / 'b'` extends it."""

    def __init__(self, substitutions: Iterable[SomeSubstitutionsType]) -> None:
        self.parts = [normalize_to_list_of_substitutions(p) for p in substitutions]

    def perform(self, context: LaunchContext) -> str:
        """The performed parts joined with the platform's separator."""
        return os.path.join(*(perform_substitutions(context, p) for p in self.parts))

    def __truediv__(self, other: SomeSubstitutionsType) -> PathJoinSubstitution:
        joined = PathJoinSubstitution([])
        joined.parts = [*self.parts, normalize_to_list_of_substitutions(other)]
        return joined

    def describe(self) -> str:
        """The parts, as launch shows them."""
        return 'PathJoin(' + ', '.join(describe_substitutions(p) for p in self.parts) + ')'


class ThisLaunchFileDir(Substitution):
    """The directory of the launch file being read."""

    def perform(self, context: LaunchContext) -> str:
        """The directory of the launch file being read; a failure outside one."""
        value = context.get_locals_as_dict().get('current_launch_file_directory')
        if value is None:
            raise SubstitutionFailure('ThisLaunchFileDir used outside of a launch file')
        return str(value)

    def describe(self) -> str:
        """As launch shows it."""
        return 'ThisLaunchFileDir()'


class ThisLaunchFile(Substitution):
    """The path of the launch file being read."""

    def perform(self, context: LaunchContext) -> str:
        """The path of the launch file being read; a failure outside one."""
        value = context.get_locals_as_dict().get('current_launch_file_path')
        if value is None:
            raise SubstitutionFailure('ThisLaunchFile used outside of a launch file')
        return str(value)

    def describe(self) -> str:
        """As launch shows it."""
        return 'ThisLaunchFile()'


class FindExecutable(Substitution):
    """The full path of an executable on PATH."""

    def __init__(self, *, name: SomeSubstitutionsType) -> None:
        self.name = normalize_to_list_of_substitutions(name)

    def perform(self, context: LaunchContext) -> str:
        """The executable's full path on the launch's PATH; a failure when absent."""
        name = perform_substitutions(context, self.name)
        found = shutil.which(name, path=context.environment.get('PATH'))
        if found is None:
            raise SubstitutionFailure(f"executable '{name}' not found on the PATH")
        return found

    def describe(self) -> str:
        """The executable's name, as launch shows it."""
        return f'FindExec({describe_substitutions(self.name)})'


class AnonName(Substitution):
    """`name` with a random suffix, the same one for the whole launch."""

    def __init__(self, name: SomeSubstitutionsType) -> None:
        self.name = normalize_to_list_of_substitutions(name)

    def perform(self, context: LaunchContext) -> str:
        """The name with its suffix, the same for the whole launch."""
        name = perform_substitutions(context, self.name)
        return context.anonymous_name(name, lambda: f'{name}_{secrets.token_hex(8)}')

    def describe(self) -> str:
        """The name, as launch shows it."""
        return f'AnonName({describe_substitutions(self.name)})'


class Command(Substitution):
    """The standard output of a command (e.g. `xacro robot.urdf.xacro`), run without a
    shell; a failing command stops the launch with its error output."""

    def __init__(self, command: SomeSubstitutionsType, *, on_stderr: str = 'fail') -> None:
        self.command = normalize_to_list_of_substitutions(command)
        self.on_stderr = on_stderr

    def perform(self, context: LaunchContext) -> str:
        """The command's standard output; a failure when it fails (or writes to stderr,
        unless `on_stderr` allows it)."""
        text = perform_substitutions(context, self.command)
        try:
            argv = shlex.split(text)
            # a ROS shell's environment, as for the launch's processes: `xacro` on PATH and
            # its `ament_index_python` answered by the package index
            env = child_environment(
                context.environment, workspaces=context.package_index.workspaces()
            )
            done = subprocess.run(argv, capture_output=True, text=True, env=env, check=False)
        except (OSError, ValueError) as e:
            raise SubstitutionFailure(f"command '{text}' could not run: {e}") from None
        if done.returncode != 0:
            raise SubstitutionFailure(
                f"executed command failed. Command: {text}\nCaptured stderr output: {done.stderr}"
            )
        if done.stderr and self.on_stderr == 'fail':
            raise SubstitutionFailure(
                f'executed command showed stderr output. Command: {text}\n'
                f'Captured stderr output: {done.stderr}'
            )
        return done.stdout

    def describe(self) -> str:
        """The command, as launch shows it."""
        return f'Command({describe_substitutions(self.command)})'


# -- expressions ---------------------------------------------------------------------------------

_EXPRESSION_BUILTINS = {
    'abs': abs,
    'bool': bool,
    'float': float,
    'int': int,
    'len': len,
    'max': max,
    'min': min,
    'round': round,
    'str': str,
    'True': True,
    'False': False,
    'None': None,
}


class PythonExpression(Substitution):
    """The value of a Python expression written in the launch file (after substitution),
    with the `math` module's names and a few plain builtins in scope."""

    def __init__(self, expression: SomeSubstitutionsType) -> None:
        self.expression = normalize_to_list_of_substitutions(expression)

    def perform(self, context: LaunchContext) -> str:
        """The expression's value as text, evaluated with math and a few safe builtins."""
        text = perform_substitutions(context, self.expression)
        scope: dict[str, object] = {'__builtins__': _EXPRESSION_BUILTINS, 'math': math}
        scope.update({k: v for k, v in vars(math).items() if not k.startswith('_')})
        try:
            return str(eval(text, scope, {}))  # the launch file's own expression
        except Exception as e:
            raise SubstitutionFailure(f"expression '{text}' failed: {e}") from None

    def describe(self) -> str:
        """The expression, as launch shows it."""
        return f'PythonExpr({describe_substitutions(self.expression)})'


_TRUE = ('true', '1')
_FALSE = ('false', '0')


def evaluate_condition_expression(context: LaunchContext, subs: Sequence[Substitution]) -> bool:
    """'true'/'1' → True, 'false'/'0' → False (any case); anything else is an error."""
    text = perform_substitutions(context, subs).strip().lower()
    if text in _TRUE:
        return True
    if text in _FALSE:
        return False
    raise InvalidConditionExpressionError(
        f"Unexpected condition expression '{text}', expected one of: {', '.join(_TRUE + _FALSE)}"
    )


class NotSubstitution(Substitution):
    """'true' when the value is false and the reverse."""

    def __init__(self, value: SomeSubstitutionsType) -> None:
        self.value = normalize_to_list_of_substitutions(value)

    def perform(self, context: LaunchContext) -> str:
        """'true' or 'false'."""
        return str(not evaluate_condition_expression(context, self.value)).lower()


class AndSubstitution(Substitution):
    """'true' when both values are true."""

    def __init__(self, left: SomeSubstitutionsType, right: SomeSubstitutionsType) -> None:
        self.left = normalize_to_list_of_substitutions(left)
        self.right = normalize_to_list_of_substitutions(right)

    def perform(self, context: LaunchContext) -> str:
        """'true' or 'false'."""
        return str(
            evaluate_condition_expression(context, self.left)
            and evaluate_condition_expression(context, self.right)
        ).lower()


class OrSubstitution(AndSubstitution):
    """'true' when either value is true."""

    def perform(self, context: LaunchContext) -> str:
        """'true' or 'false'."""
        return str(
            evaluate_condition_expression(context, self.left)
            or evaluate_condition_expression(context, self.right)
        ).lower()


class EqualsSubstitution(Substitution):
    """'true' when both values perform to the same text (booleans compared as such)."""

    def __init__(self, left: object, right: object) -> None:
        self.left = normalize_to_list_of_substitutions(_plain(left))
        self.right = normalize_to_list_of_substitutions(_plain(right))

    def _equal(self, context: LaunchContext) -> bool:
        a = perform_substitutions(context, self.left)
        b = perform_substitutions(context, self.right)
        return _canonical(a) == _canonical(b)

    def perform(self, context: LaunchContext) -> str:
        """'true' or 'false'."""
        return str(self._equal(context)).lower()


class NotEqualsSubstitution(EqualsSubstitution):
    """'true' when the values differ."""

    def perform(self, context: LaunchContext) -> str:
        """'true' or 'false'."""
        return str(not self._equal(context)).lower()


class IfElseSubstitution(Substitution):
    """`if_value` when the condition is true, else `else_value`."""

    def __init__(
        self,
        condition: SomeSubstitutionsType,
        if_value: SomeSubstitutionsType = '',
        else_value: SomeSubstitutionsType = '',
    ) -> None:
        self.condition = normalize_to_list_of_substitutions(condition)
        self.if_value = normalize_to_list_of_substitutions(if_value)
        self.else_value = normalize_to_list_of_substitutions(else_value)

    def perform(self, context: LaunchContext) -> str:
        """The chosen value, performed."""
        chosen = (
            self.if_value
            if evaluate_condition_expression(context, self.condition)
            else self.else_value
        )
        return perform_substitutions(context, chosen)


def _plain(value: object) -> object:
    return '' if value is None else value


def _canonical(text: str) -> str:
    lowered = text.strip().lower()
    if lowered in ('true', 'false'):
        return lowered
    try:
        return repr(float(lowered))
    except ValueError:
        return text
