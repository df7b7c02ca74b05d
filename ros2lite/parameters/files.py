"""ROS 2 parameter YAML files: which entries apply to a node, and the `param dump` layout.

A file maps node names to ``ros__parameters``. Node names follow rcl's rules: a leading ``/``
is implied, namespaces may be written as nested keys (``ns: {node: {ros__parameters: …}}``),
``/*`` stands for exactly one name segment and ``/**`` for any number of them (so ``/**``
alone matches every node). Nested parameter maps become dotted names (``a: {b: 1}`` is
``a.b``). Later entries win over earlier ones, in file order.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, cast

from ros2lite.exceptions import Ros2liteError
from ros2lite.parameter import PARAMETER_SEPARATOR_STRING, Parameter

if TYPE_CHECKING:
    import yaml

    from ros2lite.msgs.rcl_interfaces import msg as _rcl_msg
    from ros2lite.parameter import AllowableParameterValue, Parameter

# values are whatever the YAML holds until a Parameter is made of them (which checks them)
Values = dict[str, object]

PARAMS_KEY = "ros__parameters"
WILDCARD = "/**"


class ParamsFileError(Ros2liteError, ValueError):
    """The file cannot be read or is not a ROS 2 parameters file; the message says why."""


class _Entries(dict[object, object]):
    """A YAML mapping that also keeps every (key, value) pair in file order: rcl reads a
    parameters file as a stream, so a node key written twice contributes both entries."""

    pairs: list[tuple[object, object]]


@functools.cache
def _entries_loader() -> type[yaml.SafeLoader]:
    """A SafeLoader whose mappings remember repeated keys (see `_Entries`)."""
    import yaml

    class Loader(yaml.SafeLoader):
        pass

    def mapping(loader: yaml.SafeLoader, node: yaml.MappingNode) -> _Entries:
        loader.flatten_mapping(node)
        entries = _Entries()
        entries.pairs = []
        for key_node, value_node in node.value:
            key = loader.construct_object(key_node, deep=True)
            value = loader.construct_object(value_node, deep=True)
            entries.pairs.append((key, value))
            entries[key] = value
        return entries

    Loader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, mapping)
    return Loader


def read_params_file(path: str | Path) -> list[tuple[str, Values]]:
    """Every (node name, flattened parameters) entry of the file, in file order (a node key
    that appears twice gives two entries, as rcl reads it)."""
    from ros2lite.util.files import ReadRefused, read_text_bounded
    from ros2lite.util.safe_yaml import YamlInputError, load

    path = Path(path)
    try:
        text = read_text_bounded(path, "a parameters file")
        data = load(text, "the file", loader_class=_entries_loader())
    except ReadRefused as e:
        raise ParamsFileError(f"Couldn't read parameters file '{path}': {e.reason}") from None
    except (OSError, YamlInputError) as e:
        why = (e.strerror if isinstance(e, OSError) else None) or e
        raise ParamsFileError(f"Couldn't read parameters file '{path}': {why}") from None
    if data is None:
        return []
    if not isinstance(data, dict):
        raise ParamsFileError(f"Parameters file '{path}' must map node names to parameters")
    entries: list[tuple[str, Values]] = []
    _collect(path, data, "", entries)
    return entries


def _collect(
    path: Path, tree: Mapping[object, object], prefix: str, out: list[tuple[str, Values]]
) -> None:
    for key, section in getattr(tree, "pairs", tree.items()):
        name = f"{prefix}/{str(key).strip('/')}" if prefix else _absolute(str(key))
        if not isinstance(section, dict):
            raise ParamsFileError(f"Parameters file '{path}': '{name}' needs '{PARAMS_KEY}'")
        if PARAMS_KEY in section:
            params = section[PARAMS_KEY]
            if not isinstance(params, dict):
                raise ParamsFileError(
                    f"Parameters file '{path}': '{name}' needs '{PARAMS_KEY}' to be a map"
                )
            out.append((name, flatten(params)))
            rest = {k: v for k, v in section.items() if k != PARAMS_KEY}
        else:
            rest = section  # a namespace level
        if rest:
            _collect(path, rest, name, out)


def _absolute(name: str) -> str:
    return name if name.startswith("/") else "/" + name


def flatten(tree: Mapping[object, object], prefix: str = "") -> Values:
    """Nested maps as dotted names: {'a': {'b': 1}} → {'a.b': 1}."""
    out: Values = {}
    for key, value in tree.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out.update(flatten(value, name + PARAMETER_SEPARATOR_STRING))
        else:
            out[name] = value
    return out


def node_pattern(name: str) -> re.Pattern[str]:
    """rcl's matching: '/*' is one name segment, '/**' any number of them, the rest literal."""
    parts = re.split(r"(/\*\*|/\*)", _absolute(name))
    regex = "".join(
        "(/[^/]+)*" if p == "/**" else "(/[^/]+)" if p == "/*" else re.escape(p) for p in parts
    )
    return re.compile(regex)


def matches(pattern: str, node_fqn: str) -> bool:
    """Whether a file's node name (maybe with wildcards) stands for `node_fqn`."""
    return node_pattern(pattern).fullmatch(node_fqn) is not None


def values_for_node(path: str | Path, node_fqn: str, *, use_wildcard: bool = True) -> Values:
    """The parameters this file gives the node (`use_wildcard=False` skips pattern entries)."""
    values: Values = {}
    for name, params in read_params_file(path):
        if "*" in name and not use_wildcard:
            continue
        if matches(name, node_fqn):
            values.update(params)
    return values


def parameters_for_node(path: str | Path, node_fqn: str, use_wildcard: bool) -> list[Parameter]:
    """The file's parameters for the node as Parameters; an error naming the nodes the file
    has when it has none for this one, or naming a value that cannot be a parameter."""
    values = values_for_node(path, node_fqn, use_wildcard=use_wildcard)
    if not values:
        nodes = [name for name, _ in read_params_file(path)]
        raise ParamsFileError(
            f"Param file does not contain parameters for {node_fqn}, only for nodes: {nodes}"
        )
    params = []
    for name, value in values.items():
        try:
            # Parameter() checks that the YAML value is one a parameter can hold
            params.append(Parameter(name, value=cast("AllowableParameterValue", value)))
        except (TypeError, ValueError) as e:
            raise ParamsFileError(f"Parameter '{name}' in '{path}': {e}") from None
    return params


def parameter_dict_from_yaml_file(
    parameter_file: str | Path,
    use_wildcard: bool = False,
    target_nodes: list[str] | None = None,
    namespace: str = "",
) -> dict[str, _rcl_msg.Parameter]:
    """rclpy's reading of a parameters file: name → rcl_interfaces/msg/Parameter of the
    entries of `target_nodes` (every node's when None), after the `/**` ones when
    `use_wildcard`; names get `namespace.` in front. FileNotFoundError for a missing file,
    RuntimeError when the file has no entry asked for."""
    from ros2lite.parameter import Parameter

    path = Path(parameter_file)
    if not path.is_file():
        raise FileNotFoundError(f"No such parameters file: '{path}'")
    entries = read_params_file(path)
    chosen = [(n, p) for n, p in entries if use_wildcard and n == WILDCARD]
    if target_nodes:
        names = {n for n, _ in entries}
        for target in target_nodes:
            if _absolute(target) not in names:
                raise RuntimeError(
                    f"Param file does not contain parameters for {target}, only for nodes: "
                    f"{sorted(names)}"
                )
        wanted = {_absolute(t) for t in target_nodes}
        chosen += [(n, p) for n, p in entries if n in wanted]
    else:
        chosen += [(n, p) for n, p in entries if n != WILDCARD]
    if not chosen:
        raise RuntimeError("Param file does not contain selected parameters")
    values: Values = {}
    for _, params in chosen:
        values.update(params)
    prefix = namespace + PARAMETER_SEPARATOR_STRING if namespace else ""
    out: dict[str, _rcl_msg.Parameter] = {}
    for name, value in values.items():
        try:
            parameter = Parameter(prefix + name, value=cast("AllowableParameterValue", value))
            out[prefix + name] = parameter.to_parameter_msg()
        except (TypeError, ValueError) as e:
            raise ParamsFileError(f"Parameter '{name}' in '{path}': {e}") from None
    return out


def dump_tree(values: Mapping[str, object]) -> dict[str, object]:
    """Dotted names back into nested maps (what `param dump` writes)."""
    tree: dict[str, object] = {}
    for name in sorted(values):
        node = tree
        *parents, leaf = name.split(PARAMETER_SEPARATOR_STRING)
        for i, part in enumerate(parents):
            child = node.setdefault(part, {})
            if not isinstance(child, dict):  # 'a' and 'a.b' both exist: keep the rest flat
                leaf = PARAMETER_SEPARATOR_STRING.join([*parents[i:], leaf])
                break
            node = child
        node[leaf] = values[name]
    return tree


def dump_yaml(node_fqn: str, values: Mapping[str, object]) -> str:
    """A parameters file for one node, as `ros2 param dump` prints it (keys sorted)."""
    import yaml

    text: str = yaml.dump({node_fqn: {PARAMS_KEY: dump_tree(values)}}, default_flow_style=False)
    return text


def dump_file_name(node_fqn: str) -> str:
    """`/ns/node` → `ns__node.yaml`, the name `param dump --output-dir` writes."""
    return node_fqn.lstrip("/").replace("/", "__") + ".yaml"
