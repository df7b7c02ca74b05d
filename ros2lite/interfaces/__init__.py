"""The ROS type system: definitions, classes, CDR codecs, RIHS01 hashes and text forms.

Everything here is pure Python and imports nothing heavy; PyYAML is only imported by the
YAML helpers when they are called.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from .cdr import Codec, codec
from .classes import ActionType, Message, ServiceType
from .classes import get_interface as _get_interface
from .errors import CdrError, FieldError, InterfaceError, UnknownInterfaceError
from .hashing import type_hash as _type_hash
from .registry import Registry, default_registry, normalize_name

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.type_support import Msg

    from .convert import FormatOptions

__all__ = [
    'ActionType',
    'CdrError',
    'FieldError',
    'InterfaceError',
    'Message',
    'Registry',
    'ServiceType',
    'UnknownInterfaceError',
    'definition_text',
    'deserialize',
    'get_interface',
    'list_interfaces',
    'message_to_csv',
    'message_to_dict',
    'message_to_yaml',
    'serialize',
    'set_message_fields',
    'type_hash',
]


def get_interface(name: str) -> Any:
    """Class for 'pkg/msg|srv|action/Name' (or 'pkg/Name' for messages, or a sub-type)."""
    return _get_interface(name)


def type_hash(name: str) -> str:
    """'RIHS01_…' type hash of any interface or generated sub-type."""
    return _type_hash(normalize_name(name))


def serialize(msg: Msg) -> bytes:
    """CDR bytes (little-endian, with the 4-byte encapsulation header) of a message."""
    if not isinstance(msg, Message):
        raise TypeError(f'not a ros2lite message: {msg!r}')
    c: Codec | None = getattr(type(msg), '_CODEC', None)
    if c is None:
        c = codec(msg._TYPE_NAME)
    return c.serialize(msg)


_BY_NAME: dict[str | type[Message], Codec] = {}


def deserialize(type_or_name: str | type[Message], data: bytes | bytearray | memoryview) -> Message:
    """Decode CDR bytes of either byte order into a message object."""
    c = _BY_NAME.get(type_or_name)
    if c is None or c.reg is not default_registry():
        name = type_or_name if isinstance(type_or_name, str) else type_or_name._TYPE_NAME
        c = codec(normalize_name(name), default_registry())
        _BY_NAME[type_or_name] = c
    return c.deserialize(data)


def list_interfaces() -> list[str]:
    """Every 'pkg/kind/Name' definition visible on the search path, sorted."""
    return default_registry().all_interfaces()


def definition_text(name: str) -> str:
    """The rosbag2 'ros2msg' schema text: the type's file plus every dependency once."""
    from .text import definition_text as _definition_text

    return _definition_text(normalize_name(name), default_registry())


def message_to_dict(msg: Message, **opts: Unpack[FormatOptions]) -> dict[str, object]:
    """Nested plain dict/list/scalar form of a message, in field order (rosidl_runtime_py's)."""
    from .convert import message_to_dict as _f

    return _f(msg, **opts)


def message_to_yaml(
    msg: Message, *, flow_style: bool = False, fast: bool = True, **opts: Unpack[FormatOptions]
) -> str:
    """YAML text exactly as `ros2 topic echo` prints a message."""
    from .convert import message_to_yaml as _f

    return _f(msg, flow_style=flow_style, fast=fast, **opts)


def message_to_csv(msg: Message, **opts: Unpack[FormatOptions]) -> str:
    """Comma-separated leaf values, as `ros2 topic echo --csv` prints them."""
    from .convert import message_to_csv as _f

    return _f(msg, **opts)


def set_message_fields(
    msg: Message,
    values: dict[str, Any] | str,
    *,
    expand_header_auto: bool = False,
    expand_time_now: bool = False,
) -> list[Callable[[Message], None]]:
    """Fill `msg` from a dict or YAML mapping text (rosidl_runtime_py coercions).

    Returns the stamp setters that 'header: auto' / 'stamp: now' asked for.
    """
    from .convert import set_message_fields as _f

    return _f(msg, values, expand_header_auto=expand_header_auto, expand_time_now=expand_time_now)
