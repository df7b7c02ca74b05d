"""ROS names: validation, expansion and hidden names, with rcl's rules and rclpy's exceptions.

A name is rejected here exactly when rcl would reject it, because the graph, the data keys
and remapping all depend on names agreeing byte for byte between ros2lite and real ROS nodes.
The wire encoding of names (mangling into key chunks) is :mod:`ros2lite.transport.keys`' job.
"""

from __future__ import annotations

import re

from ros2lite.exceptions import (
    InvalidNamespaceException,
    InvalidNodeNameException,
    InvalidServiceNameException,
    InvalidTopicNameException,
    NameValidationException,
)

__all__ = [
    'ACTION_NAMESPACE',
    'absolute_node_name',
    'action_entity_name',
    'expand_topic_name',
    'is_hidden_name',
    'node_fqn',
    'normalize_namespace',
    'split_fqn',
    'topic_or_service_is_hidden',
    'validate_full_topic_name',
    'validate_namespace',
    'validate_node_name',
    'validate_topic_name',
]

_TOKEN_RE = re.compile(r'[A-Za-z_][A-Za-z0-9_]*')
_SUBST_RE = re.compile(r'\{([^{}]*)\}')


def _name_error(is_service: bool) -> type[NameValidationException]:
    return InvalidServiceNameException if is_service else InvalidTopicNameException


def _check_tokens(
    name: str, what: str, error: type[NameValidationException], shown: str | None = None
) -> None:
    label = shown if shown is not None else repr(name)
    for token in name.split('/'):
        if token and token[0].isdigit():
            raise error(f'{what} {label} is invalid: token {token!r} must not start with a number')


def _unallowed(name: str, allowed: str) -> bool:
    return any(not (c.isascii() and (c.isalnum() or c in allowed)) for c in name)


def validate_topic_name(name: str, *, is_service: bool = False) -> None:
    """Check a topic/service name as a user may write it (relative, ``~`` and ``{}`` allowed),
    as ``rcl_validate_topic_name`` does; the exception says which of rcl's rules is broken."""
    what = 'service name' if is_service else 'topic name'
    error = _name_error(is_service)
    if not name:
        raise error(f'{what} is invalid: must not be empty')
    if _unallowed(name, '_/~{}'):
        raise error(
            f"{what} {name!r} is invalid: must not contain characters other than "
            "alphanumerics, '_', '~', '{', '}' or '/'"
        )
    if name[0].isdigit():
        raise error(f'{what} {name!r} is invalid: must not start with a number')
    if name.endswith('/'):
        raise error(f"{what} {name!r} is invalid: must not end with '/'")
    if '//' in name:
        raise error(f"{what} {name!r} is invalid: must not contain repeated '/'")
    if '~' in name[1:] or (name.startswith('~') and len(name) > 1 and name[1] != '/'):
        raise error(f"{what} {name!r} is invalid: '~' is only allowed as '~' or '~/…' at the start")
    depth = 0
    for c in name:
        if c == '{':
            depth += 1
            if depth > 1:
                raise error(f"{what} {name!r} is invalid: nested '{{'")
        elif c == '}':
            depth -= 1
            if depth < 0:
                raise error(f"{what} {name!r} is invalid: unbalanced '}}'")
    if depth:
        raise error(f"{what} {name!r} is invalid: unbalanced '{{'")
    for m in _SUBST_RE.finditer(name):
        if not _TOKEN_RE.fullmatch(m.group(1)):
            raise error(
                f'{what} {name!r} is invalid: substitution {m.group(0)!r} must be alphanumerics '
                "or '_', not starting with a number"
            )
    _check_tokens(_SUBST_RE.sub('x', name.replace('~', 'x')), what, error, repr(name))


def validate_full_topic_name(name: str, *, is_service: bool = False) -> None:
    """Check an expanded, absolute topic/service name (``/ns/name``), as rmw does."""
    _check_absolute(name, 'service name' if is_service else 'topic name', _name_error(is_service))


def _check_absolute(name: str, what: str, error: type[NameValidationException]) -> None:
    """Rules shared by absolute topic names and namespaces (rmw's, in its order)."""
    if not name:
        raise error(f'{what} is invalid: must not be empty')
    if not name.startswith('/'):
        raise error(f"{what} {name!r} is invalid: must be absolute (start with '/')")
    if name == '/' and what == 'namespace':
        return
    if _unallowed(name, '_/'):
        raise error(
            f"{what} {name!r} is invalid: must not contain characters other than "
            "alphanumerics, '_' or '/'"
        )
    if '//' in name:
        raise error(f"{what} {name!r} is invalid: must not contain repeated '/'")
    if name.endswith('/'):
        raise error(f"{what} {name!r} is invalid: must not end with '/'")
    _check_tokens(name, what, error)


def validate_node_name(name: str) -> None:
    """A node name is one token: letters, digits and '_', not starting with a number."""
    if not name:
        raise InvalidNodeNameException('node name is invalid: must not be empty')
    if _unallowed(name, '_'):
        raise InvalidNodeNameException(
            f"node name {name!r} is invalid: must not contain characters other than "
            "alphanumerics or '_'"
        )
    if name[0].isdigit():
        raise InvalidNodeNameException(
            f'node name {name!r} is invalid: must not start with a number'
        )


def validate_namespace(namespace: str) -> None:
    """An absolute namespace: ``/`` or ``/a/b`` (no trailing '/', no '//')."""
    _check_absolute(namespace, 'namespace', InvalidNamespaceException)


def normalize_namespace(namespace: str | None) -> str:
    """rclpy's leniency: ``None``/``""`` → ``/`` and ``robot1`` → ``/robot1``; then validate."""
    ns = namespace or '/'
    if not ns.startswith('/'):
        ns = '/' + ns
    if len(ns) > 1:
        ns = ns.rstrip('/') or '/'
    validate_namespace(ns)
    return ns


def node_fqn(namespace: str, node_name: str) -> str:
    """``/ns`` + ``name`` → ``/ns/name`` (and ``/`` + ``name`` → ``/name``)."""
    return ('' if namespace == '/' else namespace) + '/' + node_name


def split_fqn(fqn: str) -> tuple[str, str]:
    """``/a/b/name`` → (``/a/b``, ``name``); ``/name`` → (``/``, ``name``)."""
    head, _, tail = fqn.rpartition('/')
    return (head or '/'), tail


def absolute_node_name(name: str) -> str:
    """A node name as users type it (``talker`` or ``/ns/talker``) made absolute."""
    return name if name.startswith('/') else '/' + name


def expand_topic_name(
    name: str, node_name: str, namespace: str, *, is_service: bool = False
) -> str:
    """Expand a user-written name into the absolute one, like ``rcl_expand_topic_name``.

    ``~`` becomes the node's fully qualified name, ``{node}``/``{ns}``/``{namespace}`` are
    substituted, and relative names are put under the node's namespace.
    """
    validate_topic_name(name, is_service=is_service)
    validate_node_name(node_name)
    validate_namespace(namespace)
    if name.startswith('~'):
        name = node_fqn(namespace, node_name) + name[1:]
    subs = {'node': node_name, 'ns': namespace, 'namespace': namespace}

    def repl(m: re.Match[str]) -> str:
        key = m.group(1)
        if key not in subs:
            what = 'service name' if is_service else 'topic name'
            raise _name_error(is_service)(
                f'{what} {name!r} is invalid: unknown substitution {{{key}}}'
            )
        return subs[key]

    name = _SUBST_RE.sub(repl, name)
    if not name.startswith('/'):
        name = ('' if namespace == '/' else namespace) + '/' + name
    name = re.sub(r'/{2,}', '/', name)
    validate_full_topic_name(name, is_service=is_service)
    return name


# rcl_action puts an action's three services and two topics under `<action>/_action/`
ACTION_NAMESPACE = '/_action/'


def action_entity_name(action: str, entity: str) -> str:
    """The full name of one of an action's entities: `/fib` + `feedback` →
    `/fib/_action/feedback`."""
    return f'{action}{ACTION_NAMESPACE}{entity}'


def is_hidden_name(name: str) -> bool:
    """Hidden topics, services and nodes have a token starting with '_' (ros2cli hides them)."""
    return any(tok.startswith('_') for tok in name.split('/') if tok)


# rclpy's name for the same rule
topic_or_service_is_hidden = is_hidden_name
