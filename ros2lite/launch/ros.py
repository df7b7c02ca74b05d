"""The ROS part of launch (what launch_ros adds): Node, namespaces, parameters, remaps and
finding packages — all through the package index, so source workspaces work unbuilt.

A Node becomes ``<executable> [arguments] --ros-args -r __node:=<name> -r __ns:=<ns>
--params-file <file>… -r <from>:=<to>… [ros_arguments]``. Parameters given as dicts (and
global ones from SetParameter) are written to a fresh parameter file (``/**:
ros__parameters:``) deleted when the launch ends; text values are read as YAML, so
``'1'`` is an integer and ``'true'`` a bool, as launch_ros does.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Iterable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeAlias

from ros2lite.names import NameValidationException, normalize_namespace, validate_namespace
from ros2lite.util.files import ReadRefused, read_text_bounded

from .actions import Action, ActionOptions, Entities, path_of
from .context import ParameterData
from .errors import LaunchError
from .execute import ExecuteProcess
from .find_package import FindPackagePrefix, FindPackageShare
from .substitutions import (
    SomeSubstitutionsType,
    Substitution,
    describe_substitutions,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.pkg.executables import PackageExecutable

    from .context import LaunchContext

__all__ = [
    'FindPackagePrefix',
    'FindPackageShare',
    'Node',
    'ParameterFile',
    'ParameterValue',
    'PushRosNamespace',
    'SetParameter',
    'SetParametersFromFile',
    'SetRemap',
]


# -- parameters ----------------------------------------------------------------------------------

# one entry of Node(parameters=...): a dict of values, or a parameter file
ParameterEntry: TypeAlias = (
    'Mapping[str, object] | Mapping[Substitution, object] | ParameterFile'
    ' | SomeSubstitutionsType | Path'
)


class ParameterValue:
    """A parameter value with an explicit type (None: read text as YAML)."""

    def __init__(self, value: object, *, value_type: object = None) -> None:
        self.value = value
        self.value_type = value_type


class ParameterFile:
    """A parameter file; with `allow_substs`, `$(var …)` and friends inside it are
    performed before the node reads it."""

    def __init__(
        self, param_file: SomeSubstitutionsType | Path, *, allow_substs: bool = False
    ) -> None:
        self.param_file = param_file
        self.allow_substs = allow_substs


def _yaml_value(text: str) -> ParameterData:
    """Text as launch_ros reads it: a YAML scalar or a list of one scalar type; else text."""
    from ros2lite.util.safe_yaml import YamlInputError, load

    try:
        value = load(text, 'a launch value')
    except YamlInputError:
        return text
    if isinstance(value, (bool, int, float, str)):
        return value
    if isinstance(value, list) and value:
        first = type(value[0])
        if first in (bool, int, float, str) and all(type(v) is first for v in value):
            return value
    return text


def _is_substitutions(value: object) -> bool:
    return isinstance(value, Substitution) or (
        isinstance(value, (list, tuple))
        and bool(value)
        and any(isinstance(v, Substitution) for v in value)
        and all(isinstance(v, (Substitution, str)) for v in value)
    )


def evaluate_parameter(context: LaunchContext, value: object) -> ParameterData:
    """The value a node gets for one parameter entry."""
    if isinstance(value, ParameterValue):
        inner = value.value
        if _is_substitutions(inner) or isinstance(inner, str):
            text = perform_substitutions(context, normalize_to_list_of_substitutions(inner))
            if value.value_type is None:
                return _yaml_value(text)
            if value.value_type is str:
                return text
            return _typed(text, value.value_type)
        return evaluate_parameter(context, inner)
    if _is_substitutions(value):
        return _yaml_value(
            perform_substitutions(context, normalize_to_list_of_substitutions(value))
        )
    if isinstance(value, str):
        return _yaml_value(value)
    if isinstance(value, (list, tuple)):
        return [
            perform_substitutions(context, normalize_to_list_of_substitutions(v))
            if isinstance(v, Substitution)
            else v
            for v in value
        ]
    if isinstance(value, (bool, int, float)) or value is None:
        return value
    raise LaunchError(f'unsupported parameter value {value!r}')


def _typed(text: str, value_type: object) -> ParameterData:
    from ros2lite.util.safe_yaml import YamlInputError, load

    try:
        parsed = load(text, 'a launch parameter value')
    except YamlInputError:
        parsed = text
    if value_type is float and isinstance(parsed, int) and not isinstance(parsed, bool):
        return float(parsed)
    if isinstance(value_type, type) and not isinstance(parsed, value_type):
        raise LaunchError(f"parameter value '{text}' is not a {value_type.__name__}")
    return parsed


def _flatten(
    context: LaunchContext,
    params: Mapping[str, object] | Mapping[Substitution, object],
    prefix: str = '',
) -> dict[str, ParameterData]:
    flat: dict[str, ParameterData] = {}
    for key, value in params.items():
        name = perform_substitutions(context, normalize_to_list_of_substitutions(key))
        full = f'{prefix}{name}'
        if isinstance(value, Mapping):
            flat.update(_flatten(context, value, full + '.'))
        else:
            flat[full] = evaluate_parameter(context, value)
    return flat


class SetParameter(Action):
    """A parameter every Node after it (in this scope) gets."""

    def __init__(
        self, name: SomeSubstitutionsType, value: object, **kwargs: Unpack[ActionOptions]
    ) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)
        self.value = value

    def execute(self, context: LaunchContext) -> Entities | None:
        """Add the evaluated parameter to the current scope's global parameters."""
        name = perform_substitutions(context, self.name)
        context.scope.global_params.append((name, evaluate_parameter(context, self.value)))
        return None

    def describe(self) -> str:
        """The parameter's name, for introspection."""
        return f'SetParameter({describe_substitutions(self.name)})'


class SetParametersFromFile(Action):
    """A parameter file every Node after it (in this scope) reads."""

    def __init__(self, filename: SomeSubstitutionsType, **kwargs: Unpack[ActionOptions]) -> None:
        super().__init__(**kwargs)
        self.filename = normalize_to_list_of_substitutions(filename)

    def execute(self, context: LaunchContext) -> Entities | None:
        """Add the file to the current scope's global parameters."""
        context.scope.global_params.append(Path(perform_substitutions(context, self.filename)))
        return None


class SetRemap(Action):
    """A remapping every Node after it (in this scope) gets."""

    def __init__(
        self,
        src: SomeSubstitutionsType,
        dst: SomeSubstitutionsType,
        **kwargs: Unpack[ActionOptions],
    ):
        super().__init__(**kwargs)
        self.src = normalize_to_list_of_substitutions(src)
        self.dst = normalize_to_list_of_substitutions(dst)

    def execute(self, context: LaunchContext) -> Entities | None:
        """Add the remapping to the current scope."""
        context.scope.remaps.append(
            (perform_substitutions(context, self.src), perform_substitutions(context, self.dst))
        )
        return None


def _join_namespace(base: str | None, namespace: str | None) -> str | None:
    if not namespace:
        return base
    if namespace.startswith('/') or not base or base == '/':
        joined = namespace if namespace.startswith('/') else '/' + namespace
    else:
        joined = base.rstrip('/') + '/' + namespace
    return joined


class PushRosNamespace(Action):
    """Puts the Nodes after it (in this scope) under a namespace (relative ones nest)."""

    def __init__(self, namespace: SomeSubstitutionsType, **kwargs: Unpack[ActionOptions]) -> None:
        super().__init__(**kwargs)
        self.namespace = normalize_to_list_of_substitutions(namespace)

    def execute(self, context: LaunchContext) -> Entities | None:
        """Join the namespace to the current scope's one (a valid ROS namespace, or an error)."""
        text = perform_substitutions(context, self.namespace).strip()
        joined = _join_namespace(context.scope.ros_namespace, text)
        context.scope.ros_namespace = _valid_namespace(joined) if joined else joined
        return None

    def describe(self) -> str:
        """The namespace, for introspection."""
        return f'PushRosNamespace({describe_substitutions(self.namespace)})'


def _valid_namespace(namespace: str) -> str:
    try:
        ns = normalize_namespace(namespace.rstrip('/') or '/')
        validate_namespace(ns)
    except NameValidationException as e:
        raise LaunchError(f"invalid namespace '{namespace}': {e}") from None
    return ns


# -- Node ----------------------------------------------------------------------------------------


class Node(ExecuteProcess):
    """A ROS node from a package: found through the package index (workspaces included),
    started with its name, namespace, parameters and remappings as ROS arguments."""

    def __init__(
        self,
        *,
        executable: SomeSubstitutionsType,
        package: SomeSubstitutionsType | None = None,
        name: SomeSubstitutionsType | None = None,
        namespace: SomeSubstitutionsType | None = None,
        exec_name: SomeSubstitutionsType | None = None,
        parameters: Sequence[ParameterEntry] | None = None,
        remappings: Iterable[tuple[SomeSubstitutionsType, SomeSubstitutionsType]] | None = None,
        ros_arguments: Iterable[SomeSubstitutionsType] | None = None,
        arguments: Iterable[SomeSubstitutionsType] | None = None,
        **kwargs: Any,  # ExecuteProcess's keywords, passed on as they are
    ) -> None:
        super().__init__(cmd=[], name=exec_name, **kwargs)
        self.package = None if package is None else normalize_to_list_of_substitutions(package)
        self.executable = normalize_to_list_of_substitutions(executable)
        self.node_name = None if name is None else normalize_to_list_of_substitutions(name)
        self.node_namespace = (
            None if namespace is None else normalize_to_list_of_substitutions(namespace)
        )
        self.parameters = list(parameters or [])
        self.remappings = [
            (normalize_to_list_of_substitutions(a), normalize_to_list_of_substitutions(b))
            for a, b in (remappings or [])
        ]
        self.ros_arguments = [normalize_to_list_of_substitutions(a) for a in ros_arguments or []]
        self.node_arguments = [normalize_to_list_of_substitutions(a) for a in arguments or []]
        self._resolved: PackageExecutable | None = None

    def _find(self, context: LaunchContext) -> PackageExecutable:
        from ros2lite.pkg.executables import resolve_executable

        exe_name = perform_substitutions(context, self.executable)
        if self.package is None:
            raise LaunchError(
                f"Node '{exe_name}' needs a package: ros2lite runs package executables"
            )
        package = perform_substitutions(context, self.package)
        resolved = resolve_executable(package, exe_name, index=context.package_index)
        if resolved.note:
            context.service.log('INFO', 'launch', resolved.note)
        return resolved.executable

    def _params_file(self, context: LaunchContext, values: dict[str, ParameterData]) -> str:
        import yaml

        fd, path = tempfile.mkstemp(prefix='launch_params_', suffix='.yaml')
        with os.fdopen(fd, 'w', encoding='utf-8') as out:
            yaml.safe_dump({'/**': {'ros__parameters': values}}, out, sort_keys=False)
        context.service.add_temp_file(path)
        return path

    def _substituted_file(self, context: LaunchContext, path: str) -> str:
        from .frontend.substitutions import parse_substitutions

        try:
            text = read_text_bounded(path, 'a parameter file')
        except ReadRefused as e:
            raise LaunchError(f"parameter file '{path}': {e.reason}") from None
        performed = perform_substitutions(context, parse_substitutions(text))
        fd, out_path = tempfile.mkstemp(prefix='launch_params_', suffix='.yaml')
        with os.fdopen(fd, 'w', encoding='utf-8') as out:
            out.write(performed)
        context.service.add_temp_file(out_path)
        return out_path

    def _parameter_args(self, context: LaunchContext) -> list[str]:
        args: list[str] = []
        pending: dict[str, ParameterData] = {}

        def flush() -> None:
            if pending:
                args.extend(['--params-file', self._params_file(context, dict(pending))])
                pending.clear()

        for entry in context.scope.global_params:
            if isinstance(entry, Path):
                flush()
                args.extend(['--params-file', str(entry)])
            else:
                pending[entry[0]] = entry[1]
        for param in self.parameters:
            if isinstance(param, Mapping):
                pending.update(_flatten(context, param))
                continue
            flush()
            if isinstance(param, ParameterFile):
                path = path_of(param.param_file, context)
                if param.allow_substs:
                    path = self._substituted_file(context, path)
            else:
                path = path_of(param, context)
            args.extend(['--params-file', path])
        flush()
        return args

    def ros_args(self, context: LaunchContext) -> list[str]:
        """The `--ros-args` part of the command (without the flag itself)."""
        out: list[str] = []
        if self.node_name is not None:
            out += ['-r', f'__node:={perform_substitutions(context, self.node_name)}']
        own_ns = (
            None
            if self.node_namespace is None
            else perform_substitutions(context, self.node_namespace).strip()
        )
        namespace = _join_namespace(context.scope.ros_namespace, own_ns)
        if namespace:
            out += ['-r', f'__ns:={_valid_namespace(namespace)}']
        out += self._parameter_args(context)
        for src, dst in context.scope.remaps:
            out += ['-r', f'{src}:={dst}']
        for src_subs, dst_subs in self.remappings:
            src = perform_substitutions(context, src_subs)
            dst = perform_substitutions(context, dst_subs)
            out += ['-r', f'{src}:={dst}']
        for arg in self.ros_arguments:
            out.append(perform_substitutions(context, arg))
        return out

    def command(self, context: LaunchContext) -> tuple[list[str], list[str], list[str]]:
        """The package executable with the node's arguments and `--ros-args` part."""
        exe = self._find(context)
        self._resolved = exe
        argv = [perform_substitutions(context, a) for a in self.node_arguments]
        ros = self.ros_args(context)
        if ros:
            argv += ['--ros-args', *ros]
        return exe.command(argv), [exe.path(), *argv], list(exe.pythonpath)

    def label(self, context: LaunchContext, cmd: list[str]) -> str:
        """The process' name: the executable's name unless `exec_name` is given."""
        if self.name is not None:
            return perform_substitutions(context, self.name)
        return self._resolved.name if self._resolved is not None else super().label(context, cmd)

    def describe(self) -> str:
        """Package and executable, for introspection."""
        pkg = describe_substitutions(self.package) if self.package else '?'
        return f'Node(package={pkg}, executable={describe_substitutions(self.executable)})'
