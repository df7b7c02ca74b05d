"""Generated XCDR1 codecs, one serializer and one deserializer per type and byte order: the
codec table (a :class:`Codec` per type, cached on its class).  The code generators live in
:mod:`ros2lite.interfaces.cdr_gen`; a codec builds each function on its first call.
"""

from __future__ import annotations

import struct
from collections.abc import Callable
from typing import TYPE_CHECKING

from .cdr_gen import Des, build_deserializer, build_fast_decoder, build_serializer
from .classes import Message, factory
from .errors import CdrError
from .registry import Registry, default_registry

if TYPE_CHECKING:
    from ros2lite.type_support import Msg


class Codec:
    """Serializer and deserializers of one type; each is generated on its first call."""

    __slots__ = ('_des_be', '_des_le', '_des_lenient', '_ser', 'name', 'reg')

    def __init__(self, name: str, reg: Registry) -> None:
        self.name, self.reg = name, reg
        self._ser: Callable[[Msg], bytes] = self._first_ser
        self._des_le: Des = self._first_des_le
        self._des_be: Des = self._first_des_be
        self._des_lenient: dict[bool, Des] = {}

    def _first_ser(self, msg: Msg) -> bytes:
        self._ser = build_serializer(self.name, self.reg)
        return self._ser(msg)

    def _first_des_le(self, data: bytes, o: int) -> tuple[Message, int]:
        self._des_le = build_deserializer(self.name, self.reg, True)
        return self._des_le(data, o)

    def _first_des_be(self, data: bytes, o: int) -> tuple[Message, int]:
        self._des_be = build_deserializer(self.name, self.reg, False)
        return self._des_be(data, o)

    def raw_serializer(self) -> Callable[[Msg], bytes]:
        """The generated function itself, for hot loops that handle errors themselves."""
        if self._ser == self._first_ser:
            self._ser = build_serializer(self.name, self.reg)
        return self._ser

    def fast_deserializer(self) -> Callable[[bytes], Message]:
        """A lean decoder for the common case (little-endian, well-formed bytes); anything
        else falls back to `deserialize`, which gives the precise error."""
        return build_fast_decoder(self.name, self.reg, self.deserialize)

    def serialize(self, msg: Msg) -> bytes:
        """CDR bytes with the little-endian encapsulation header; CdrError on bad fields."""
        try:
            return self._ser(msg)
        except (struct.error, AttributeError, TypeError, UnicodeEncodeError) as e:
            raise CdrError(f'cannot serialize {self.name}: {e}') from None

    def deserialize(self, data: bytes | bytearray | memoryview) -> Message:
        """Decode one payload; anything that is not a valid encoding of this type (however
        it came: short, garbage, huge lengths) raises CdrError, never another error."""
        if type(data) is not bytes:
            data = bytes(data)
        try:
            try:
                if data[1] == 1 and data[0] == 0:
                    msg, end = self._des_le(data, 4)
                elif data[1] == 0 and data[0] == 0:
                    msg, end = self._des_be(data, 4)
                else:
                    raise CdrError(f'not a CDR payload for {self.name} (bad encapsulation header)')
            except UnicodeDecodeError:
                msg, end = self._lenient(data[1] == 1)(data, 4)
        except CdrError:
            raise
        except (struct.error, IndexError, ValueError, OverflowError, MemoryError) as e:
            if isinstance(e, IndexError) and len(data) < 4:
                raise CdrError(
                    f'truncated {self.name} payload: {len(data)} bytes, not even a CDR header'
                ) from None
            raise CdrError(f'truncated or corrupt {self.name} payload: {e}') from None
        if end > len(data):
            raise CdrError(f'truncated {self.name} payload: needs {end} bytes, got {len(data)}')
        return msg

    def _lenient(self, little: bool) -> Des:
        """The decoder that replaces bad UTF-8 (built once per byte order: a stream of such
        samples must not compile code per sample)."""
        des = self._des_lenient.get(little)
        if des is None:
            des = self._des_lenient[little] = build_deserializer(
                self.name, self.reg, little, lenient=True
            )
        return des


def codec(name: str, reg: Registry | None = None) -> Codec:
    """The codec of a type (from the default registry unless told), cached on its class so
    lookups cost one attribute access."""
    if reg is None:
        reg = default_registry()
    cls = factory(reg).message_class(name)
    c: Codec | None = cls.__dict__.get('_CODEC')
    if c is None:
        c = Codec(cls._TYPE_NAME, reg)
        cls._CODEC = c  # type: ignore[attr-defined]
    return c


def service_codecs(service_type: str) -> tuple[Codec, Codec]:
    """(request codec, response codec) of a service type 'pkg/srv/Name'."""
    return codec(f'{service_type}_Request'), codec(f'{service_type}_Response')
