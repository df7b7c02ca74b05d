"""Is this a type ros2lite can publish, serve or act on? The checks rclpy's type_support
module offers, for ros2lite's interface classes.

A ros2lite message, service or action class carries its type name (`_TYPE_NAME`); classes
generated for rclpy's C type support (`_TYPE_SUPPORT`) are not ros2lite's, and are refused
with a message that says where the right ones come from.
"""

from __future__ import annotations

from ros2lite.exceptions import NoTypeSupportImportedException
from ros2lite.interfaces.classes import ActionType, Message, ServiceType

__all__ = [
    'check_for_type_support',
    'check_is_valid_action_type',
    'check_is_valid_msg_type',
    'check_is_valid_srv_type',
]


_MISSING = object()


def check_for_type_support(msg_or_srv_type: object) -> None:
    """Pass for ros2lite's interface classes. AttributeError for what is no interface at
    all; NoTypeSupportImportedException for a foreign (rclpy-generated) one."""
    if getattr(msg_or_srv_type, '_TYPE_NAME', None):
        return
    support = getattr(msg_or_srv_type, '_TYPE_SUPPORT', _MISSING)
    if support is _MISSING:
        raise AttributeError(f'{msg_or_srv_type!r} is no interface class (no _TYPE_SUPPORT)')
    if support is None:
        importer = getattr(type(msg_or_srv_type), '__import_type_support__', None)
        if importer is not None:
            importer()
    raise NoTypeSupportImportedException(
        f'{msg_or_srv_type!r} was generated for rclpy, not ros2lite: import it from '
        "'<package>.msg|srv|action' in a shell set up by `ros2lite env`"
    )


def _is_subclass(value: object, base: type) -> bool:
    return isinstance(value, type) and issubclass(value, base)


def check_is_valid_msg_type(msg_type: object) -> None:
    """RuntimeError unless `msg_type` is a message class."""
    check_for_type_support(msg_type)
    if not _is_subclass(msg_type, Message):
        raise RuntimeError(f'The message type provided is not valid: {msg_type}')


def check_is_valid_srv_type(srv_type: object) -> None:
    """RuntimeError unless `srv_type` is a service class."""
    check_for_type_support(srv_type)
    if not _is_subclass(srv_type, ServiceType):
        raise RuntimeError(f'The service type provided is not valid: {srv_type}')


def check_is_valid_action_type(action_type: object) -> None:
    """RuntimeError unless `action_type` is an action class."""
    check_for_type_support(action_type)
    if not _is_subclass(action_type, ActionType):
        raise RuntimeError(f'The action type provided is not valid: {action_type}')
