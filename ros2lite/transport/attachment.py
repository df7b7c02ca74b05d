"""The rmw_zenoh attachment carried by every publication, request and reply.

Subscribers in rmw_zenoh drop samples without one, and services match replies to requests
through its sequence number and client GID, so every sample we send needs it.  Current
releases use a fixed 33-byte layout; early Jazzy/Humble releases used a 77-byte keyed
layout that we can still read (and write, for talking to those peers).
"""

from __future__ import annotations

import struct
import time
from dataclasses import dataclass

import xxhash

__all__ = [
    "ATTACHMENT_SIZE",
    "GID_SIZE",
    "LEGACY_ATTACHMENT_SIZE",
    "PACK_CURRENT",
    "Attachment",
    "decode_attachment",
    "encode_attachment",
    "encode_legacy_attachment",
    "gid_from_token",
    "is_legacy_attachment",
    "pack_attachment",
    "source_timestamp",
    "unpack_attachment",
]

GID_SIZE = 16
ATTACHMENT_SIZE = 33
LEGACY_ATTACHMENT_SIZE = 77

_CURRENT = struct.Struct("<qqB")
# the whole current layout in one struct: seq, timestamp, GID length, GID
_PACKED = struct.Struct("<qqB16s")
_I64 = struct.Struct("<q")

_K_SEQ = b"\x0fsequence_number"
_K_TS = b"\x10source_timestamp"
_K_GID = b"\x0asource_gid"


@dataclass(frozen=True)
class Attachment:
    """Sequence number, source timestamp (ns since the UNIX epoch) and 16-byte source GID."""

    sequence_number: int
    source_timestamp: int
    source_gid: bytes

    def __post_init__(self) -> None:
        if len(self.source_gid) != GID_SIZE:
            raise ValueError(f"GID must be {GID_SIZE} bytes, got {len(self.source_gid)}")

    @property
    def is_valid(self) -> bool:
        """rmw_zenoh rejects samples whose sequence number or timestamp is negative."""
        return self.sequence_number >= 0 and self.source_timestamp >= 0

    def encode(self) -> bytes:
        """The 33-byte attachment rmw_zenoh sends with each sample."""
        return encode_attachment(self.sequence_number, self.source_timestamp, self.source_gid)


def encode_attachment(sequence_number: int, source_timestamp: int | None, gid: bytes) -> bytes:
    """The 33-byte current format; ``source_timestamp=None`` means now."""
    if len(gid) != GID_SIZE:
        raise ValueError(f"GID must be {GID_SIZE} bytes, got {len(gid)}")
    ts = time.time_ns() if source_timestamp is None else source_timestamp
    return _CURRENT.pack(sequence_number, ts, GID_SIZE) + bytes(gid)


def pack_attachment(sequence_number: int, source_timestamp: int, gid: bytes) -> bytes:
    """The hot-path encoder (publish, request, reply): no checks, one struct call."""
    return _PACKED.pack(sequence_number, source_timestamp, GID_SIZE, gid)


PACK_CURRENT = _PACKED.pack
"""`PACK_CURRENT(seq, timestamp, GID_SIZE, gid)`: pack_attachment without its Python call
(a publisher calls it per message)."""


def unpack_attachment(data: bytes) -> tuple[int, int, bytes] | None:
    """(seq, timestamp, gid) of either layout, or None when it is neither; the current
    layout is unpacked inline because every received sample comes through here."""
    if len(data) == ATTACHMENT_SIZE and data[16] == GID_SIZE:
        seq, ts, _, gid = _PACKED.unpack(data)
        return seq, ts, gid
    try:
        a = decode_attachment(data)
    except ValueError:
        return None
    return a.sequence_number, a.source_timestamp, a.source_gid


_TIMESTAMP = struct.Struct("<q").unpack_from


def source_timestamp(data: bytes) -> int | None:
    """The publisher's timestamp of an attachment of either layout, or None when it is
    neither (the bag recorder asks this per message: the current layout costs no tuple)."""
    if len(data) == ATTACHMENT_SIZE and data[16] == GID_SIZE:
        return int(_TIMESTAMP(data, 8)[0])
    fields = unpack_attachment(data)
    return fields[1] if fields is not None else None


def encode_legacy_attachment(sequence_number: int, source_timestamp: int, gid: bytes) -> bytes:
    """The 77-byte keyed format of Jazzy 0.2.0-0.2.3 / Humble 0.1.0-0.1.1."""
    if len(gid) != GID_SIZE:
        raise ValueError(f"GID must be {GID_SIZE} bytes, got {len(gid)}")
    return (
        _K_SEQ
        + _I64.pack(sequence_number)
        + _K_TS
        + _I64.pack(source_timestamp)
        + _K_GID
        + bytes([GID_SIZE])
        + bytes(gid)
    )


def is_legacy_attachment(data: bytes) -> bool:
    """True when ``data`` starts like the old keyed format (``0f 'sequence_number'``)."""
    return bytes(data[: len(_K_SEQ)]) == _K_SEQ


def decode_attachment(data: bytes | bytearray | memoryview) -> Attachment:
    """Decode either format; raises ``ValueError`` when it is neither."""
    raw = bytes(data)
    if len(raw) == ATTACHMENT_SIZE and raw[16] == GID_SIZE:
        seq, ts, _ = _CURRENT.unpack_from(raw)
        return Attachment(seq, ts, raw[17:])
    if len(raw) == LEGACY_ATTACHMENT_SIZE and is_legacy_attachment(raw):
        pos = len(_K_SEQ)
        (seq,) = _I64.unpack_from(raw, pos)
        pos += 8
        if raw[pos : pos + len(_K_TS)] != _K_TS:
            raise ValueError("legacy attachment: 'source_timestamp' key missing")
        pos += len(_K_TS)
        (ts,) = _I64.unpack_from(raw, pos)
        pos += 8
        if raw[pos : pos + len(_K_GID) + 1] != _K_GID + bytes([GID_SIZE]):
            raise ValueError("legacy attachment: 'source_gid' key missing")
        pos += len(_K_GID) + 1
        return Attachment(seq, ts, raw[pos : pos + GID_SIZE])
    raise ValueError(
        f"unrecognised rmw_zenoh attachment ({len(raw)} bytes; expected "
        f"{ATTACHMENT_SIZE} or the {LEGACY_ATTACHMENT_SIZE}-byte legacy format)"
    )


def gid_from_token(liveliness_key: str) -> bytes:
    """The entity GID rmw_zenoh derives: XXH3-128 of the token key, low64 then high64, LE."""
    h = xxhash.xxh3_128_intdigest(liveliness_key.encode("utf-8"))
    return h.to_bytes(GID_SIZE, "little")
