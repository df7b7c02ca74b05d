"""XML/YAML elements → launch actions, one builder per element type.

Element names are those of launch and launch_ros (`arg`, `let`, `node`, `executable`,
`include`, `group`, `push-ros-namespace`, `set_parameter`, `set_remap`, `set_env`,
`unset_env`, `timer`, `log`, `shutdown`); dashes and underscores are interchangeable. Every
action takes `if`/`unless`.
"""

from __future__ import annotations

import shlex
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from ..actions import (
    Action,
    ActionOptions,
    DeclareLaunchArgument,
    LaunchDescriptionEntity,
    SetEnvironmentVariable,
    SetLaunchConfiguration,
    UnsetEnvironmentVariable,
)
from ..conditions import IfCondition, UnlessCondition
from ..errors import InvalidFrontendLaunchFileError
from ..execute import ExecuteProcess
from ..flow import GroupAction, IncludeLaunchDescription, LogInfo, Shutdown, TimerAction
from ..sources import AnyLaunchDescriptionSource
from ..substitutions import Substitution, TextSubstitution
from .entity import Entity
from .substitutions import parse_substitutions

if TYPE_CHECKING:
    from ..ros import ParameterEntry

__all__ = ['BUILDERS', 'build', 'build_all']


def _condition(e: Entity) -> ActionOptions:
    if_ = e.subs('if')
    unless = e.subs('unless')
    if if_ is not None and unless is not None:
        raise e.error("use 'if' or 'unless', not both")
    if if_ is not None:
        return {'condition': IfCondition(if_)}
    if unless is not None:
        return {'condition': UnlessCondition(unless)}
    return {}


def split_words(subs: list[Substitution]) -> list[list[Substitution]]:
    """A command line split into words as a shell would (quotes group, backslashes escape);
    each substitution stays whole inside the word it is written in."""
    text = ''
    for i, sub in enumerate(subs):
        if isinstance(sub, TextSubstitution):
            if '\x00' in sub.text:
                raise InvalidFrontendLaunchFileError('a command may not contain NUL characters')
            text += sub.text
        else:
            text += f'\x00{i}\x00'
    try:
        words = shlex.split(text)
    except ValueError as e:
        raise InvalidFrontendLaunchFileError(f'cannot split command {text!r}: {e}') from None
    out: list[list[Substitution]] = []
    for word in words:
        parts: list[Substitution] = []
        for n, piece in enumerate(word.split('\x00')):
            if n % 2:
                parts.append(subs[int(piece)])
            elif piece:
                parts.append(TextSubstitution(text=piece))
        out.append(parts or [TextSubstitution(text='')])
    return out


def _arg(e: Entity) -> Action:
    name = e.text('name', optional=False)
    assert name is not None
    choices = [c.text('value', optional=False) or '' for c in e.child_list('choice')]
    return DeclareLaunchArgument(
        name,
        default_value=e.subs('default'),
        description=e.text('description'),
        choices=choices or None,
        **_condition(e),
    )


def _let(e: Entity) -> Action:
    return SetLaunchConfiguration(
        e.subs('name', optional=False) or [],
        e.subs('value', optional=False) or [],
        **_condition(e),
    )


# ExecuteProcess keyword ← the launch file attribute that gives it
_PROCESS_ATTRIBUTES = (
    ('output', 'output'),
    ('prefix', 'launch-prefix'),
    ('sigterm_timeout', 'sigterm_timeout'),
    ('sigkill_timeout', 'sigkill_timeout'),
    ('respawn', 'respawn'),
)


def _process_options(e: Entity) -> dict[str, Any]:  # ExecuteProcess's keywords
    options: dict[str, Any] = {}
    for key, attribute in _PROCESS_ATTRIBUTES:
        value = e.subs(attribute)
        if value is not None:
            options[key] = value
    delay = e.number('respawn_delay')
    if delay is not None:
        options['respawn_delay'] = delay
    envs = e.child_list('env')
    if envs:
        options['additional_env'] = {
            tuple(env.subs('name', optional=False) or []): env.subs('value', optional=False)
            for env in envs
        }
    return options


def _executable(e: Entity) -> Action:
    cmd = e.subs('cmd', optional=False) or []
    args = e.subs('args')
    words = split_words(cmd) + (split_words(args) if args else [])
    return ExecuteProcess(
        cmd=words,
        name=e.subs('name'),
        cwd=e.subs('cwd'),
        shell=e.flag('shell', False),
        **_process_options(e),
        **_condition(e),
    )


def _param_value(p: Entity) -> object:
    value = p.value('value')
    sep = p.text('value-sep')
    if isinstance(value, str):
        if sep:
            return [parse_substitutions(v) for v in value.split(sep)]
        return parse_substitutions(value)
    return value


def _params(e: Entity) -> list[ParameterEntry]:
    """A node's parameters: dicts for name/value (nested params become `a.b`), paths for
    `from`."""
    out: list[ParameterEntry] = []
    for p in e.child_list('param'):
        source = p.subs('from')
        if source is not None:
            out.append(source)
            continue
        out.append({_param_name(p): _param_tree(p)})
    return out


def _param_name(p: Entity) -> str:
    name = p.text('name')
    if not name:
        raise p.error("a <param> needs 'name' (with 'value' or nested params) or 'from'")
    return name


def _param_tree(p: Entity) -> object:
    nested = p.child_list('param')
    if nested:
        return {_param_name(child): _param_tree(child) for child in nested}
    if p.raw('value') is None:
        raise p.error(f"parameter '{p.text('name')}' has no value")
    return _param_value(p)


def _node(e: Entity) -> Action:
    from ..ros import Node

    args = e.subs('args')
    ros_args = e.subs('ros_args')
    remaps = [
        (r.subs('from', optional=False) or [], r.subs('to', optional=False) or [])
        for r in e.child_list('remap')
    ]
    return Node(
        package=e.subs('pkg', optional=False),
        executable=e.subs('exec', optional=False) or [],
        name=e.subs('name'),
        namespace=e.subs('namespace') if e.raw('namespace') is not None else e.subs('ns'),
        exec_name=e.subs('exec_name'),
        parameters=_params(e),
        remappings=remaps,
        arguments=split_words(args) if args else None,
        ros_arguments=split_words(ros_args) if ros_args else None,
        **_process_options(e),
        **_condition(e),
    )


def _include(e: Entity) -> Action:
    arguments = [
        (a.subs('name', optional=False) or [], a.subs('value', optional=False) or [])
        for a in e.child_list('arg')
    ]
    return IncludeLaunchDescription(
        AnyLaunchDescriptionSource(e.subs('file', optional=False) or []),
        launch_arguments=arguments,
        **_condition(e),
    )


def _group(e: Entity) -> Action:
    return GroupAction(
        build_all(e.children()),
        scoped=e.flag('scoped', True),
        forwarding=e.flag('forwarding', True),
        **_condition(e),
    )


def _push_ros_namespace(e: Entity) -> Action:
    from ..ros import PushRosNamespace

    return PushRosNamespace(e.subs('namespace', optional=False) or [], **_condition(e))


def _set_parameter(e: Entity) -> Action:
    from ..ros import SetParameter

    if e.raw('value') is None:
        raise e.error("missing attribute 'value'")
    return SetParameter(e.subs('name', optional=False) or [], _param_value(e), **_condition(e))


def _set_remap(e: Entity) -> Action:
    from ..ros import SetRemap

    return SetRemap(
        e.subs('from', optional=False) or [],
        e.subs('to', optional=False) or [],
        **_condition(e),
    )


def _set_env(e: Entity) -> Action:
    return SetEnvironmentVariable(
        e.subs('name', optional=False) or [],
        e.subs('value', optional=False) or [],
        **_condition(e),
    )


def _unset_env(e: Entity) -> Action:
    return UnsetEnvironmentVariable(e.subs('name', optional=False) or [], **_condition(e))


def _timer(e: Entity) -> Action:
    return TimerAction(
        period=e.subs('period', optional=False) or [],
        actions=build_all(e.children()),
        **_condition(e),
    )


def _log(e: Entity) -> Action:
    return LogInfo(msg=e.subs('message', optional=False) or [], **_condition(e))


def _shutdown(e: Entity) -> Action:
    reason = e.subs('reason')
    return Shutdown(reason=reason if reason is not None else 'reason not given', **_condition(e))


BUILDERS: dict[str, Callable[[Entity], Action]] = {
    'arg': _arg,
    'let': _let,
    'node': _node,
    'executable': _executable,
    'include': _include,
    'group': _group,
    'push_ros_namespace': _push_ros_namespace,
    'set_parameter': _set_parameter,
    'set_remap': _set_remap,
    'set_env': _set_env,
    'unset_env': _unset_env,
    'timer': _timer,
    'log': _log,
    'shutdown': _shutdown,
}


def build(e: Entity) -> LaunchDescriptionEntity:
    """The action for one element."""
    builder = BUILDERS.get(e.type_name.replace('-', '_'))
    if builder is None:
        raise e.error(
            'unknown launch element; known: '
            + ', '.join(sorted(n.replace('_', '-') for n in BUILDERS))
        )
    return builder(e)


def build_all(entities: list[Entity]) -> list[LaunchDescriptionEntity]:
    """The launch actions of a list of frontend entities, in order."""
    return [build(e) for e in entities]
