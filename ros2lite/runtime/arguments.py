"""`--ros-args` parsing with rcl's rules, so `ros2lite run pkg exe --ros-args -r …` behaves.

Supported: ``-r/--remap [node:]from:=to`` (including ``__node``/``__name`` and ``__ns``),
``-p/--param [node:]name:=value`` (YAML-typed), ``--params-file FILE``,
``--log-level [name:=]LEVEL`` and ``-e/--enclave``.  Params files are named here and read
by :mod:`ros2lite.parameters.node_api` (which imports this module, never the other way).
"""

from __future__ import annotations

import sys
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path

from ros2lite.exceptions import Ros2liteError
from ros2lite.util.safe_yaml import YamlInputError, load

LOG_LEVELS = {
    'debug': 10,
    'info': 20,
    'warn': 30,
    'warning': 30,
    'error': 40,
    'fatal': 50,
    'unset': 0,
}


class RosArgsError(Ros2liteError, ValueError):
    """Malformed --ros-args; the message says which argument and why."""


@dataclass
class Remap:
    """One `-r from:=to` rule (for one node when `node` is given)."""

    node: str | None  # only applies to this node name when given
    source: str
    target: str


@dataclass
class RosArgs:
    """What `--ros-args` said: remaps, parameters, params files, log levels, enclave."""

    remaps: list[Remap] = field(default_factory=list)
    # node → name → value (as the YAML reads; a Parameter checks it)
    params: dict[str | None, dict[str, object]] = field(default_factory=dict)
    params_files: list[Path] = field(default_factory=list)
    log_levels: dict[str | None, int] = field(default_factory=dict)
    enclave: str | None = None
    # --enable/--disable-rosout-logs and -stdout-logs; None: not given (enabled)
    rosout_logs: bool | None = None
    stdout_logs: bool | None = None
    # -p rules and params files in the order given: a later one wins, as in rcl
    # (a params file's path, or a -p rule's (node or None, name, value))
    param_sources: list[Path | tuple[str | None, str, object]] = field(default_factory=list)

    def merge(self, other: RosArgs) -> RosArgs:
        """Node-local arguments (`other`) take precedence over global ones."""
        merged = RosArgs(
            self.remaps + other.remaps,
            {},
            self.params_files + other.params_files,
            {**self.log_levels, **other.log_levels},
            other.enclave or self.enclave,
            other.rosout_logs if other.rosout_logs is not None else self.rosout_logs,
            other.stdout_logs if other.stdout_logs is not None else self.stdout_logs,
            self.param_sources + other.param_sources,
        )
        for source in (self.params, other.params):
            for node, values in source.items():
                merged.params.setdefault(node, {}).update(values)
        return merged

    def node_name_override(self, node: str) -> str | None:
        """The name `__node:=` gives this node, if any."""
        return self._special(node, ('__node', '__name'))

    def namespace_override(self, node: str) -> str | None:
        """The namespace `__ns:=` gives this node, if any."""
        return self._special(node, ('__ns',))

    def _special(self, node: str, keys: tuple[str, ...]) -> str | None:
        found = None
        for r in self.remaps:
            if r.source in keys and r.node in (None, node):
                found = r.target
        return found


def _split_assignment(text: str, what: str) -> tuple[str | None, str, str]:
    if ':=' not in text:
        raise RosArgsError(f"Couldn't parse {what} rule: '{text}' (expected 'from:=to')")
    left, _, right = text.partition(':=')
    node = None
    if ':' in left:
        node, _, left = left.partition(':')
    if not left:
        raise RosArgsError(f"Couldn't parse {what} rule: '{text}'")
    return node, left, right


def parse_value(text: str) -> object:
    """A parameter value from the command line, typed the YAML way ('1' → int)."""
    try:
        return load(text, "the value")
    except YamlInputError:
        return text


def split_ros_args(argv: list[str]) -> tuple[list[str], list[list[str]]]:
    """Separate user arguments from each `--ros-args … [--]` block."""
    user: list[str] = []
    blocks: list[list[str]] = []
    i = 0
    while i < len(argv):
        if argv[i] == '--ros-args':
            block: list[str] = []
            i += 1
            while i < len(argv) and argv[i] not in ('--', '--ros-args'):
                block.append(argv[i])
                i += 1
            if i < len(argv) and argv[i] == '--':
                i += 1
            blocks.append(block)
            continue
        user.append(argv[i])
        i += 1
    return user, blocks


def remove_ros_args(args: list[str] | None = None) -> list[str]:
    """The arguments (default: `sys.argv`) without their `--ros-args` blocks: what a
    program's own argument parser should see."""
    return split_ros_args(list(sys.argv if args is None else args))[0]


def parse_ros_args(argv: list[str] | None) -> RosArgs:
    """Parse every `--ros-args` block found in argv."""
    result = RosArgs()
    if not argv:
        return result
    _, blocks = split_ros_args(argv)
    for block in blocks:
        it = iter(block)
        for arg in it:
            if arg in ('-r', '--remap'):
                node, src, dst = _split_assignment(_next(it, arg), 'remap')
                result.remaps.append(Remap(node, src, dst))
            elif arg in ('-p', '--param'):
                node, name, value = _split_assignment(_next(it, arg), 'parameter')
                parsed = parse_value(value)
                result.params.setdefault(node, {})[name] = parsed
                result.param_sources.append((node, name, parsed))
            elif arg == '--params-file':
                path = Path(_next(it, arg))
                if not path.is_file():
                    raise RosArgsError(f"Couldn't read parameters file '{path}'")
                result.params_files.append(path)
                result.param_sources.append(path)
            elif arg == '--log-level':
                text = _next(it, arg)
                logger: str | None = None
                if ':=' in text:
                    logger, _, text = text.partition(':=')
                level = LOG_LEVELS.get(text.lower())
                if level is None:
                    raise RosArgsError(f"Invalid log level '{text}'")
                result.log_levels[logger] = level
            elif arg in ('-e', '--enclave'):
                result.enclave = _next(it, arg)
            elif arg in ('--enable-rosout-logs', '--disable-rosout-logs'):
                result.rosout_logs = arg.startswith('--enable')
            elif arg in ('--enable-stdout-logs', '--disable-stdout-logs'):
                result.stdout_logs = arg.startswith('--enable')
            elif arg in ('--enable-external-lib-logs', '--disable-external-lib-logs'):
                continue  # there is no external logging library to switch
            else:
                raise RosArgsError(f"Unknown ROS argument '{arg}'")
    return result


def _next(it: Iterator[str], flag: str) -> str:
    try:
        value: str = next(it)
    except StopIteration:
        raise RosArgsError(f"Argument '{flag}' needs a value") from None
    return value
