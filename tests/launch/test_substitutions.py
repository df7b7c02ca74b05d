"""Substitutions performed against a launch context."""

from __future__ import annotations

import os

import pytest

from ros2lite.launch.context import LaunchContext
from ros2lite.launch.errors import SubstitutionFailure
from ros2lite.launch.substitutions import (
    AndSubstitution,
    Command,
    EnvironmentVariable,
    EqualsSubstitution,
    IfElseSubstitution,
    LaunchConfiguration,
    NotSubstitution,
    PathJoinSubstitution,
    PythonExpression,
    TextSubstitution,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)


@pytest.fixture
def context() -> LaunchContext:
    ctx = LaunchContext(environment={'HOME_BASE': '/base', 'PATH': os.environ.get('PATH', '')})
    ctx.launch_configurations['robot'] = 'turtle'
    return ctx


def test_text_and_lists(context: LaunchContext) -> None:
    subs = normalize_to_list_of_substitutions(['a-', LaunchConfiguration('robot'), 3, True])
    assert perform_substitutions(context, subs) == 'a-turtle3true'
    with pytest.raises(TypeError):
        normalize_to_list_of_substitutions([object()])


def test_launch_configuration(context: LaunchContext) -> None:
    assert LaunchConfiguration('robot').perform(context) == 'turtle'
    assert (
        LaunchConfiguration('size', default=['x', LaunchConfiguration('robot')]).perform(context)
        == 'xturtle'
    )
    with pytest.raises(SubstitutionFailure, match="launch configuration 'size' does not exist"):
        LaunchConfiguration('size').perform(context)
    assert LaunchConfiguration('robot').describe() == "LaunchConfig('robot')"


def test_environment_variable(context: LaunchContext) -> None:
    assert EnvironmentVariable('HOME_BASE').perform(context) == '/base'
    assert EnvironmentVariable('NOPE', default_value='').perform(context) == ''
    with pytest.raises(SubstitutionFailure, match="environment variable 'NOPE' does not exist"):
        EnvironmentVariable('NOPE').perform(context)


def test_path_join(context: LaunchContext) -> None:
    joined = PathJoinSubstitution([EnvironmentVariable('HOME_BASE'), 'config']) / 'a.yaml'
    assert joined.perform(context) == '/base/config/a.yaml'


def test_expressions(context: LaunchContext) -> None:
    assert PythonExpression(['2 * ', '3 + float("1.5")']).perform(context) == '7.5'
    assert PythonExpression('pi > 3').perform(context) == 'True'
    assert (
        PythonExpression(["'", LaunchConfiguration('robot'), "' == 'turtle'"]).perform(context)
        == 'True'
    )
    with pytest.raises(SubstitutionFailure):
        PythonExpression('__import__("os").getcwd()').perform(context)
    assert NotSubstitution('false').perform(context) == 'true'
    assert AndSubstitution('true', '1').perform(context) == 'true'
    assert EqualsSubstitution(LaunchConfiguration('robot'), 'turtle').perform(context) == 'true'
    assert EqualsSubstitution('1.0', 1).perform(context) == 'true'
    assert IfElseSubstitution('0', 'yes', 'no').perform(context) == 'no'


def test_command(context: LaunchContext) -> None:
    assert Command(['echo ', TextSubstitution(text='hi there')]).perform(context) == 'hi there\n'
    with pytest.raises(SubstitutionFailure, match='executed command failed'):
        Command('sh -c "exit 3"').perform(context)
