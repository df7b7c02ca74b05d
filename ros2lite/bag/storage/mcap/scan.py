"""Reading an MCAP file record by record in file order: what a damaged file still holds
(chunk CRCs checked, the first damaged byte found, decompression bounded), for reading a file
without a summary and for recovering it.
"""

from __future__ import annotations

import contextlib
import os
import struct
from collections.abc import Callable, Iterator
from typing import IO, TYPE_CHECKING

if TYPE_CHECKING:
    from mcap.records import Channel, McapRecord, Metadata, Schema
    from mcap.records import Message as McapMessage

_MAGIC = b"\x89MCAP0\r\n"
_PIECE = 1 << 20  # decompressed bytes taken at a time: memory stays bounded whatever a chunk says
(_FOOTER, _SCHEMA, _CHANNEL, _MESSAGE, _CHUNK, _METADATA) = (2, 3, 4, 5, 6, 12)
_KNOWN_OPCODES = range(1, 16)  # MCAP's records; 0x80 and up are private ones (skipped)
_IN_CHUNK = (_SCHEMA, _CHANNEL, _MESSAGE)


class _Damage(Exception):
    """Where reading had to stop and why (said in the report line)."""


def _crc_table() -> tuple[list[int], dict[int, int]]:
    """zlib's CRC-32 table, and its entries' top bytes back to their index (the table is
    built so that they are all different, which makes a step of the CRC undoable)."""
    table = []
    for i in range(256):
        c = i
        for _ in range(8):
            c = (c >> 1) ^ 0xEDB88320 if c & 1 else c >> 1
        table.append(c)
    return table, {c >> 24: i for i, c in enumerate(table)}


def first_damaged_byte(data: bytes | bytearray, expected: int) -> int | None:
    """The earliest offset at which one changed byte explains `data`'s CRC-32 not being
    `expected`, or None when no single byte does (more damage than that).

    The CRC is linear: the difference of two CRCs of equal length is the CRC of the error
    alone, and a one-byte error `e` followed by `m` zero bytes has the CRC `T[e]` pushed
    through `m` zero steps. Undoing one zero step at a time from the difference finds every
    `m` that fits; the largest is the earliest offset. Every byte before it is as written
    (when the damage is one byte), so the records wholly before it can be kept."""
    import zlib

    table, back = _crc_table()
    single = {c: e for e, c in enumerate(table) if e}
    s = zlib.crc32(data) ^ expected
    n = len(data)
    found = None
    for m in range(n):
        if s in single:
            found = n - 1 - m
        i = back[s >> 24]
        s = (((s ^ table[i]) << 8) | i) & 0xFFFFFFFF
    return found


def _inflate(compression: str, data: bytes, limit: int) -> Iterator[bytes]:
    """A chunk's records in pieces of at most `_PIECE` bytes, never more than `limit` (its
    declared uncompressed size) in all: a chunk that inflates past what it declared raises
    `_Damage` there (a zip bomb costs one piece of memory, not what it inflates to). Input
    cut short yields what it holds."""
    if compression == "":
        if len(data) > limit:
            raise _Damage(f"holds {len(data)} bytes but declares {limit}")
        for i in range(0, len(data), _PIECE):
            yield data[i : i + _PIECE]
        return
    total = 0
    try:
        if compression == "zstd":
            import io

            import zstandard

            with zstandard.ZstdDecompressor().stream_reader(io.BytesIO(data)) as src:
                while piece := src.read(_PIECE):
                    total += len(piece)
                    if total > limit:
                        yield piece[: len(piece) - (total - limit)]
                        raise _Damage(f"inflates past its declared {limit} bytes")
                    yield piece
        elif compression == "lz4":
            import lz4.frame

            lz4_src = lz4.frame.LZ4FrameDecompressor()
            piece = lz4_src.decompress(data, max_length=_PIECE)
            while piece:
                total += len(piece)
                if total > limit:
                    yield piece[: len(piece) - (total - limit)]
                    raise _Damage(f"inflates past its declared {limit} bytes")
                yield piece
                if lz4_src.eof or lz4_src.needs_input:
                    break
                piece = lz4_src.decompress(b"", max_length=_PIECE)
        else:
            raise _Damage(f"has an unknown compression '{compression[:40]}'")
    except _Damage:
        raise
    except Exception as e:  # the decompressor's own complaint about its input
        raise _Damage(f"does not decompress ({e or type(e).__name__})") from None


def _parse(op: int, body: bytes | memoryview) -> McapRecord | None:
    """One record from its whole body; None when the body does not hold what the record
    says (the first bad record)."""
    import io

    from mcap.data_stream import ReadDataStream
    from mcap.records import Channel, Message, Metadata, Schema

    if op == _MESSAGE:
        if len(body) < 22:
            return None
        cid, seq, log_time, publish_time = struct.unpack_from("<HIQQ", body)
        return Message(cid, log_time, bytes(body[22:]), publish_time, seq)
    stream = ReadDataStream(io.BytesIO(body))
    kinds: dict[int, Callable[[ReadDataStream], McapRecord]] = {
        _SCHEMA: Schema.read,
        _CHANNEL: Channel.read,
        _METADATA: Metadata.read,
    }
    try:
        record = kinds[op](stream)
    except Exception:
        return None
    return record if stream.count == len(body) else None


class _ChunkHead:
    """A chunk record's fields before its records."""

    __slots__ = ("compression", "crc", "end", "records_length", "size", "start")

    def __init__(self, body: bytes) -> None:
        if len(body) < 40:
            raise _Damage("has a cut header")
        self.start, self.end, self.size, self.crc, n = struct.unpack_from("<QQQII", body)
        if n > 64 or len(body) < 32 + n + 8:
            raise _Damage("has a bad header")
        self.compression = body[32 : 32 + n].decode("ascii", errors="replace")
        (self.records_length,) = struct.unpack_from("<Q", body, 32 + n)


# a real recording's records each cost a compressor bytes (their sequence numbers and
# times change: zstd at level 19 keeps at most 0.34 of them a byte, lz4 0.07, measured on
# perfectly regular ones), so a chunk holding more than one record per compressed byte is a
# bomb of identical records (R5-B1: 22 KB of zstd holding 8.6 million empty messages)
_RECORDS_PER_BYTE = 1
_RECORDS_FLOOR = 4096


def record_bound(head: _ChunkHead, data_length: int) -> int | None:
    """The most records a compressed chunk of `data_length` bytes may honestly hold (None:
    an uncompressed chunk, bounded by its size already)."""
    if head.compression == "":
        return None
    return _RECORDS_FLOOR + _RECORDS_PER_BYTE * data_length


def _chunk_records(
    head: _ChunkHead,
    data: bytes,
    whole: bool,
    kept: list[McapRecord],
    *,
    headers_only: bool = False,
    max_records: int | None = None,
) -> str | None:
    """Put into `kept` the records of one chunk that can be trusted: all of them when its
    CRC holds; else those before the first bad record (cut short, inflating past its size,
    a length running out of the chunk, a body that does not parse, more records than its
    compressed size or `max_records` allow) or before the byte that broke its CRC. Returns
    what was wrong, or None. `headers_only` keeps messages without their data (counting
    needs no 256 MiB body held in memory)."""
    if head.size > (1 << 40):
        return f"declares an impossible size ({head.size} bytes)"
    import zlib

    good_until = head.size
    problem = None
    # a compressed chunk's CRC is taken on the pieces as they are parsed: inflating a
    # 256 MiB chunk twice doubled the cost of reading it
    crc_as_parsed = whole and bool(head.crc) and head.compression != ""
    first = len(kept)
    # uncompressed: the CRC is cheap first, and finds the damaged byte
    if whole and head.crc and not crc_as_parsed and zlib.crc32(data) != head.crc:
        where = first_damaged_byte(data, head.crc)
        if where is None:
            return "fails its CRC check"
        good_until = where
        problem = f"fails its CRC check (byte {where} of its records damaged)"
    crc = [0]
    damage: list[str] = []

    def pieces() -> Iterator[bytes]:
        try:
            for piece in _inflate(head.compression, data, head.size):
                if crc_as_parsed:
                    crc[0] = zlib.crc32(piece, crc[0])
                yield piece
        except _Damage as e:
            damage.append(str(e))
            raise

    stream = pieces()
    found = _parse_records(
        head, len(data), good_until, whole, stream, kept, headers_only, max_records
    )
    if crc_as_parsed:
        with contextlib.suppress(_Damage):
            for _ in stream:  # the rest, for the CRC, when parsing stopped early
                pass
        if damage or crc[0] != head.crc:
            del kept[first:]  # a chunk whose CRC does not hold keeps nothing
            return damage[0] if damage else "fails its CRC check"
    if found is not None:
        return problem or found
    return problem


def _parse_records(
    head: _ChunkHead,
    compressed: int,
    good_until: int,
    whole: bool,
    stream: Iterator[bytes],
    kept: list[McapRecord],
    headers_only: bool,
    max_records: int | None,
) -> str | None:
    """The records of a chunk's inflated `stream` into `kept` (see `_chunk_records`)."""
    from mcap.records import Message

    bounds = [b for b in (record_bound(head, compressed), max_records) if b is not None]
    limit = min(bounds) if bounds else None
    count = 0
    # a bytearray with its parsed front deleted: appending a piece costs the piece, not the
    # buffer (`bytes +=` made one 256 MiB record quadratic: 33 s, R5-B4)
    buf = bytearray()
    done = 0  # bytes of the records consumed so far (parsed or skipped)
    skip = 0  # bytes of a headers-only message's data still to pass over
    pending: McapRecord | None = None  # that message, kept once its record is whole
    try:
        for piece in stream:
            pos = 0
            if skip:
                step = min(skip, len(piece))
                skip -= step
                done += step
                if skip == 0 and pending is not None:
                    kept.append(pending)  # its whole record is there: it counts
                    pending = None
                if step == len(piece):
                    continue
                piece = piece[step:]
            buf += piece
            while len(buf) - pos >= 9:
                op, length = struct.unpack_from("<BQ", buf, pos)
                if op not in _IN_CHUNK and op < 0x80:
                    return f"holds a record of unknown kind ({op})"
                end = done + pos + 9 + length
                if end > head.size:
                    return "holds a record running past its end"
                if end > good_until:
                    return ""
                count += 1
                if limit is not None and count > limit:
                    return (
                        f"holds more records than its {compressed} compressed bytes can "
                        f"(over {limit}: a decompression bomb)"
                    )
                if headers_only and op == _MESSAGE and length >= 22:
                    have = min(len(buf) - pos - 9, length)
                    if have < 22:
                        count -= 1  # counted again once its header is here
                        break
                    cid, seq, log_time, publish_time = struct.unpack_from("<HIQQ", buf, pos + 9)
                    message = Message(cid, log_time, b"", publish_time, seq)
                    if have < length:
                        pending = message
                        skip = length - have
                        done += len(buf)
                        del buf[:]
                        pos = 0
                        break
                    kept.append(message)
                    pos += 9 + length
                    continue
                if len(buf) - pos - 9 < length:
                    count -= 1  # counted again once the whole record is here
                    break
                if op in _IN_CHUNK:
                    with memoryview(buf) as view:  # released before `buf` is resized
                        record = _parse(op, view[pos + 9 : pos + 9 + length])
                    if record is None:
                        return "holds a record that does not parse"
                    kept.append(record)
                pos += 9 + length
            del buf[:pos]
            done += pos
    except _Damage as e:
        return str(e)
    if buf or skip or (whole and done != head.size):
        return "ends inside a record" if whole else "is cut short"
    return None


def read_chunk_at(
    stream: IO[bytes], where: int, kept: list[McapRecord], headers_only: bool = False
) -> str | None:
    """The trusted records of the chunk record at byte `where` of `stream` into `kept` (its
    CRC checked, inflating bounded; `headers_only`: messages without their data); what was
    wrong, if aught (None: the whole chunk)."""
    size = stream.seek(0, os.SEEK_END)
    stream.seek(where)
    op_length = stream.read(9)
    if len(op_length) < 9 or op_length[0] != _CHUNK:
        return "is not where the index says"
    (length,) = struct.unpack_from("<Q", op_length, 1)
    try:
        head = _ChunkHead(stream.read(min(length, 40 + 64)))
    except _Damage as e:
        return str(e)
    start = where + 9 + 32 + len(head.compression.encode()) + 8
    end = where + 9 + length
    stream.seek(start)
    data = stream.read(max(0, min(head.records_length, end - start, size - start)))
    whole = end <= size and start + head.records_length <= end
    problem = _chunk_records(head, data, whole, kept, headers_only=headers_only)
    return problem if whole else problem or "is cut short"


class _Scan:
    """A file read record by record in file order, as `mcap recover` reads it: every record
    that can be trusted up to the first that cannot. A chunk with bad records keeps those
    before them; a chunk cut short keeps its complete records; reading goes on after a
    damaged chunk whose length is still sound. `problems` says what was lost, one line each."""

    def __init__(self, stream: IO[bytes], path: str, headers_only: bool = False) -> None:
        self.stream = stream
        self.path = path
        self.headers_only = headers_only
        self.problems: list[str] = []
        self.messages = 0
        self.schemas: dict[int, Schema] = {}
        self.channels: dict[int, Channel] = {}

    def records(self) -> Iterator[McapRecord]:
        """Schema, Channel, Message and Metadata records; a message only on a known channel."""
        from mcap.records import Channel, Message, Schema

        for record in self._records():
            if isinstance(record, Message):
                if record.channel_id not in self.channels:
                    continue
                self.messages += 1
            elif isinstance(record, Schema):
                self.schemas[record.id] = record
            elif isinstance(record, Channel):
                self.channels[record.id] = record
            yield record

    def _stop(self, at: int, what: str) -> None:
        self.problems.append(
            f"'{self.path}' is truncated at byte {at} {what}: {self.messages} messages recovered"
        )

    def _records(self) -> Iterator[McapRecord]:
        stream = self.stream
        size = stream.seek(0, os.SEEK_END)
        stream.seek(0)
        if stream.read(8) != _MAGIC:
            self._stop(0, "before its start (not an MCAP file)")
            return
        pos = 8
        while True:
            stream.seek(pos)
            head = stream.read(9)
            if len(head) < 9:
                if head:
                    self._stop(pos, "inside a record")
                else:
                    self._stop(pos, "after a complete record (no summary)")
                return
            op, length = struct.unpack("<BQ", head)
            if op == _FOOTER:
                return
            if op not in _KNOWN_OPCODES and op < 0x80:
                self._stop(pos, f"at a record of unknown kind ({op}); the rest is unreadable")
                return
            whole = length <= size - pos - 9
            if op == _CHUNK:
                yield from self._chunk(pos, length, whole, size)
                if not whole:
                    return
            elif not whole:
                self._stop(pos + 9, "inside a record")
                return
            elif op == _MESSAGE and self.headers_only and length >= 22:
                record = _parse(op, stream.read(22))
                if record is None:
                    self._stop(pos, "at a record that does not parse; the rest is unreadable")
                    return
                yield record
            elif op == _METADATA:
                record = _parse(op, stream.read(length))
                if record is None:  # its length is sound: the records after it still read
                    self.problems.append(
                        f"'{self.path}': the metadata record at byte {pos} is damaged; skipped"
                    )
                else:
                    yield record
            elif op in (_SCHEMA, _CHANNEL, _MESSAGE):
                record = _parse(op, stream.read(length))
                if record is None:
                    self._stop(pos, "at a record that does not parse; the rest is unreadable")
                    return
                yield record
            pos += 9 + length

    def _chunk(self, pos: int, length: int, whole: bool, size: int) -> Iterator[McapRecord]:
        stream = self.stream
        fixed = stream.read(min(length, 40 + 64))
        try:
            head = _ChunkHead(fixed)
        except _Damage as e:
            if whole:
                self.problems.append(f"'{self.path}': the chunk at byte {pos} {e}; skipped")
            else:
                self._stop(size, "inside a chunk")
            return
        start = pos + 9 + 32 + len(head.compression.encode()) + 8
        stream.seek(start)
        inner_whole = whole and head.records_length <= length - (start - pos - 9)
        data = stream.read(min(head.records_length, max(0, pos + 9 + length - start)))
        kept: list[McapRecord] = []
        problem = _chunk_records(head, data, inner_whole, kept, headers_only=self.headers_only)
        before = self.messages
        yield from kept
        if not whole:
            self._stop(size, "inside a chunk")
        elif not inner_whole:
            self.problems.append(
                f"'{self.path}': the chunk at byte {pos} has a bad length: "
                f"{self.messages - before} of its messages kept, the rest dropped"
            )
        elif problem is not None:
            self.problems.append(
                f"'{self.path}': the chunk at byte {pos} {problem}: "
                f"{self.messages - before} of its messages kept, the rest dropped"
            )


def records(stream: IO[bytes], problems: list[str] | None = None) -> Iterator[McapRecord]:
    """The Schema, Channel, Message and Metadata records of a file in file order (inside its
    chunks too, and the summary's repeats), up to the first that cannot be trusted; what was
    lost goes into `problems` when the scan ends. What `mcap recover` and the MCAP project's
    streamed readers see, so their conformance files can check it."""
    scan = _Scan(stream, getattr(stream, "name", "the file"))
    try:
        yield from scan.records()
    finally:
        if problems is not None:
            problems.extend(scan.problems)


def _scan(
    stream: IO[bytes],
    on_metadata: Callable[[Metadata], object] | None = None,
    on_channel: Callable[[Channel, Schema | None], object] | None = None,
    problems: list[str] | None = None,
    headers_only: bool = False,
    path: str | None = None,
) -> Iterator[tuple[dict[int, Schema], Channel, McapMessage]]:
    """Every message record in file order that can be trusted, up to the first that cannot
    (see `_Scan`); what was lost goes into `problems` when the scan ends. `headers_only`:
    messages come without their data (for counting)."""
    from mcap.records import Channel, Message, Metadata

    name = path if path is not None else getattr(stream, "name", "the file")
    scan = _Scan(stream, str(name), headers_only)
    seen: set[int] = set()
    try:
        for record in scan.records():
            if isinstance(record, Message):
                yield scan.schemas, scan.channels[record.channel_id], record
            elif isinstance(record, Channel):
                if on_channel is not None and record.id not in seen:
                    on_channel(record, scan.schemas.get(record.schema_id))
                seen.add(record.id)
            elif isinstance(record, Metadata) and on_metadata is not None:
                on_metadata(record)
    finally:
        if problems is not None:
            problems.extend(scan.problems)
