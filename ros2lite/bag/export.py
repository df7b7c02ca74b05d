"""`bag export`: one topic of a bag into a file other tools read: CSV rows as `topic echo --csv`
prints them, JSON lines in the JSON form of `interfaces.json_form`, a Parquet table (through
the optional `pyarrow`), or the frames of an image topic as PNG files in a folder.

Messages are read in log-time order and written one at a time (Parquet: in row groups), so a
bag larger than memory exports in bounded memory. Files are created without following a
symlink.
"""

from __future__ import annotations

import io
import os
from array import array
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import IO, TYPE_CHECKING

from ros2lite.bag.errors import BagError
from ros2lite.bag.reader import Reader
from ros2lite.interfaces import message_to_csv
from ros2lite.interfaces.classes import Message
from ros2lite.interfaces.json_form import dumps, echo_record, message_to_json
from ros2lite.util.files import UnsafePathError, create_new, open_for_writing

if TYPE_CHECKING:
    from PIL.Image import Image

__all__ = [
    "FORMATS",
    "IMAGE_TYPES",
    "ExportOptions",
    "export",
    "image_of",
]

FORMATS = ("csv", "jsonl", "parquet", "png")
IMAGE_TYPES = ("sensor_msgs/msg/Image", "sensor_msgs/msg/CompressedImage")
_ROW_GROUP = 10_000  # Parquet rows held in memory before they are written


@dataclass
class ExportOptions:
    """What to export and how."""

    start: int | None = None  # ns since the epoch, included
    end: int | None = None  # included
    include_info: bool = False  # CSV: topic echo -i's columns first; others: times added
    truncate_length: int | None = None  # CSV: as topic echo's -l (None: everything)
    no_arr: bool = False
    no_str: bool = False


def _messages(
    reader: Reader, topic: str, options: ExportOptions
) -> Iterator[tuple[Message, int, int]]:
    """(message, log time, publish time) of the topic; a type that cannot be decoded stops
    the export with one line."""
    stop = None if options.end is None else options.end + 1
    for _, data, log_time, publish_time in reader.raw_messages([topic], options.start, stop):
        msg = reader.decode(topic, data)
        if not isinstance(msg, Message):
            meta = reader.topic(topic)
            raise BagError(
                f"Cannot decode the messages of '{topic}' ({meta.type if meta else '?'}): "
                "the type is neither known here nor defined in the bag"
            )
        yield msg, log_time, publish_time


def _open(path: Path) -> IO[str]:
    try:
        fd = open_for_writing(path)
    except (OSError, UnsafePathError) as e:
        raise BagError(f"Cannot write '{path}': {e}") from None
    return os.fdopen(fd, "w", encoding="utf-8", newline="")


def _csv(reader: Reader, topic: str, out: IO[str], options: ExportOptions) -> int:
    """topic echo --csv's rows, -i's four message-info columns first when asked."""
    n = 0
    for msg, log_time, publish_time in _messages(reader, topic, options):
        row = message_to_csv(
            msg,
            truncate_length=options.truncate_length,
            no_arr=options.no_arr,
            no_str=options.no_str,
        )
        if options.include_info:
            row = f"{publish_time},{log_time},0,0,{row}"
        out.write(row + "\n")
        n += 1
    return n


def _jsonl(reader: Reader, topic: str, out: IO[str], options: ExportOptions) -> int:
    """`topic echo --json`'s lines; with times, `topic echo -i`'s `{"message", "info"}` (the
    publish time as source timestamp, the log time as received; a bag keeps no sequence
    numbers)."""
    n = 0
    for msg, log_time, publish_time in _messages(reader, topic, options):
        body = message_to_json(msg, no_arr=options.no_arr, no_str=options.no_str)
        info = None
        if options.include_info:
            info = {
                "source_timestamp": publish_time,
                "received_timestamp": log_time,
                "publication_sequence_number": 0,
                "reception_sequence_number": 0,
            }
        out.write(dumps(echo_record(body, info)))
        out.write("\n")
        n += 1
    return n


def _plain(value: object) -> object:
    """A field's value as Arrow takes it: nested messages as dicts, byte arrays as bytes,
    numeric arrays as lists."""
    if isinstance(value, Message):
        return {name: _plain(getattr(value, name)) for name in value.get_fields_and_field_types()}
    if isinstance(value, array):
        return value.tobytes() if value.typecode == "B" else value.tolist()
    if isinstance(value, (list, tuple)):
        if value and all(type(v) is bytes for v in value):
            return b"".join(value)
        return [_plain(v) for v in value]
    return value


def _parquet(reader: Reader, topic: str, path: Path, options: ExportOptions) -> int:
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        raise BagError("Parquet export needs pyarrow: pip install 'ros2lite[parquet]'") from None
    n = 0
    writer = None
    rows: list[dict[str, object]] = []
    fd = None
    try:
        fd = open_for_writing(path)
    except (OSError, UnsafePathError) as e:
        raise BagError(f"Cannot write '{path}': {e}") from None
    sink = os.fdopen(fd, "wb")
    try:

        def flush() -> None:
            nonlocal writer
            table = pa.Table.from_pylist(rows)
            if writer is None:
                writer = pq.ParquetWriter(sink, table.schema)
            writer.write_table(table.cast(writer.schema))
            rows.clear()

        for msg, log_time, publish_time in _messages(reader, topic, options):
            row: dict[str, object] = {"log_time": log_time, "publish_time": publish_time}
            fields = _plain(msg)
            assert isinstance(fields, dict)
            row.update(fields)
            rows.append(row)
            n += 1
            if len(rows) >= _ROW_GROUP:
                flush()
        if rows:
            flush()
        elif writer is None:  # no message in the range: an empty table of the two times
            times = pa.schema([("log_time", pa.int64()), ("publish_time", pa.int64())])
            writer = pq.ParquetWriter(sink, times)
            writer.write_table(times.empty_table())
    except (pa.ArrowException, ValueError, TypeError) as e:
        raise BagError(f"Cannot write '{topic}' as Parquet: {e}") from None
    finally:
        if writer is not None:
            writer.close()
        sink.close()
    return n


# -- images --------------------------------------------------------------------------------------

# sensor_msgs/Image encodings → (Pillow mode of the raw bytes, channels, bytes per channel)
_RAW_MODES: dict[str, tuple[str, int, int]] = {
    "rgb8": ("RGB", 3, 1),
    "rgba8": ("RGBA", 4, 1),
    "bgr8": ("BGR", 3, 1),
    "bgra8": ("BGRA", 4, 1),
    "mono8": ("L", 1, 1),
    "8uc1": ("L", 1, 1),
    "8uc3": ("BGR", 3, 1),
    "8uc4": ("BGRA", 4, 1),
    "mono16": ("I;16", 1, 2),
    "16uc1": ("I;16", 1, 2),
}


def image_of(msg: Message) -> Image:
    """A sensor_msgs Image or CompressedImage as a Pillow image (BGR turned to RGB, 16-bit
    grey kept 16-bit); BagError with one line for an encoding it cannot show."""
    from PIL import Image as PILImage

    type_name = getattr(msg, "_TYPE_NAME", "")
    data = getattr(msg, "data", b"")
    raw = data.tobytes() if isinstance(data, array) else bytes(data)
    if type_name.endswith("CompressedImage"):
        try:
            image = PILImage.open(io.BytesIO(raw))
            image.load()
        except Exception as e:
            raise BagError(
                f"a compressed frame does not decode ({type(e).__name__}: {e})"
            ) from None
        return image
    width, height, step = int(msg.width), int(msg.height), int(msg.step)  # type: ignore[attr-defined]
    encoding = str(msg.encoding).lower()  # type: ignore[attr-defined]
    mode = _RAW_MODES.get(encoding)
    if mode is None:
        raise BagError(
            f"image encoding '{msg.encoding}' is not exported "  # type: ignore[attr-defined]
            f"(known: {', '.join(sorted(_RAW_MODES))})"
        )
    raw_mode, channels, depth = mode
    row = width * channels * depth
    if width <= 0 or height <= 0 or step < row or len(raw) < step * (height - 1) + row:
        raise BagError(f"a {width}x{height} {encoding} frame holds {len(raw)} bytes: too few")
    if depth == 2 and getattr(msg, "is_bigendian", False):
        raw_mode = "I;16B"
    rows = raw if step == row else b"".join(raw[i * step : i * step + row] for i in range(height))
    out_mode = {"BGR": "RGB", "BGRA": "RGBA"}.get(raw_mode, raw_mode)
    if raw_mode.startswith("I;16"):
        out_mode = "I;16"
    return PILImage.frombytes(out_mode, (width, height), rows, "raw", raw_mode)


def _png(reader: Reader, topic: str, folder: Path, options: ExportOptions) -> int:
    """Each frame as `<index>_<sec>.<nanosec>.png` (log time) in `folder` (made if need be;
    files already there are not overwritten)."""
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise BagError(f"Cannot create '{folder}': {e.strerror or e}") from None
    if folder.is_symlink() or not folder.is_dir():
        raise BagError(f"'{folder}' is not a folder")
    n = 0
    for msg, log_time, _ in _messages(reader, topic, options):
        try:
            image = image_of(msg)
        except BagError as e:
            raise BagError(f"frame {n} of '{topic}': {e}") from None
        sec, nsec = divmod(log_time, 1_000_000_000)
        name = folder / f"{n:06d}_{sec}.{nsec:09d}.png"
        buffer = io.BytesIO()
        image.save(buffer, format="PNG")
        try:
            fd = create_new(name)
        except (OSError, UnsafePathError) as e:
            raise BagError(f"Cannot write '{name}': {e}") from None
        with os.fdopen(fd, "wb") as f:
            f.write(buffer.getvalue())
        n += 1
    return n


def export(
    bag: str | os.PathLike[str],
    topic: str,
    fmt: str,
    output: str | os.PathLike[str],
    options: ExportOptions | None = None,
) -> int:
    """Export `topic` of `bag` as `fmt` (one of FORMATS) to `output` (a file; for png a
    folder); the number of messages written."""
    options = options or ExportOptions()
    if fmt not in FORMATS:
        raise BagError(f"Unknown export format '{fmt}' (choose from {', '.join(FORMATS)})")
    with Reader(bag) as reader:
        name = topic if reader.topic(topic) is not None or topic.startswith("/") else "/" + topic
        meta = reader.topic(name)
        if meta is None:
            raise BagError(f"The bag has no topic '{topic}'")
        if fmt == "png" and meta.type not in IMAGE_TYPES:
            raise BagError(
                f"'{name}' is {meta.type}: only {' and '.join(IMAGE_TYPES)} export as PNG"
            )
        path = Path(output)
        if fmt == "png":
            return _png(reader, name, path, options)
        if fmt == "parquet":
            return _parquet(reader, name, path, options)
        write: Callable[[Reader, str, IO[str], ExportOptions], int] = (
            _csv if fmt == "csv" else _jsonl
        )
        with _open(path) as out:
            return write(reader, name, out, options)
