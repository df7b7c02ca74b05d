"""`bag echo`: print the messages of a bag as `topic echo` prints them live (YAML, CSV, JSON
lines or raw CDR), from one topic, several or all, over a time range.

One topic echoed prints exactly what `topic echo` prints for the same messages. Several
topics put a line before each message saying its topic and log time (a `#` comment in YAML;
`topic,time,` columns in CSV), so the output still parses; in JSON each line is
`topic echo -i`'s `{"message", "info"}` object with a `"topic"` key added
(`json_form.echo_record`). Times are printed as ROS prints them (`sec.nanosec`, or the
integer nanoseconds of message info), or as local dates with `--human`.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

import click

from ..errors import CliError
from ..options import CSV_HELP, format_options
from ..parsing import command
from ..topic.common import compile_filter
from .options import TIME_HELP, bag_error, warn

if TYPE_CHECKING:
    from ros2lite.interfaces.parser import FieldType

    from ..options import MessageFormat


def ros_time(ns: int) -> str:
    """`sec.nanosec`, as `bag info` and ROS logs print a time."""
    sec, nsec = divmod(ns, 1_000_000_000)
    return f"{sec}.{nsec:09d}"


def human_time(ns: int) -> str:
    """A local date and time to the nanosecond (`bag info`'s first form)."""
    sec, nsec = divmod(ns, 1_000_000_000)
    try:
        local = time.strftime("%b %e %Y %H:%M:%S", time.localtime(sec))
    except (OverflowError, OSError, ValueError):
        return ros_time(ns)
    return f"{local}.{nsec:09d}"


class BagPrinter:
    """One bag message at a time, as text in the chosen form."""

    def __init__(
        self,
        fmt: MessageFormat,
        *,
        json: bool,
        raw: bool,
        field: list[str] | None,
        filter_fn: Callable[[object], object] | None,
        include_info: bool,
        human: bool,
        headers: bool,
    ) -> None:
        self.fmt = fmt
        self.json = json
        self.raw = raw
        self.field = field
        self.filter_fn = filter_fn
        self.include_info = include_info
        self.headers = headers
        self.when = human_time if human else ros_time
        self.stamp: Callable[[int], object] = human_time if human else int
        self.undecoded: set[str] = set()
        self.field_types: dict[str, FieldType | None] = {}  # of the --field value, per topic

    def info(self, log_time: int, publish_time: int) -> dict[str, object]:
        """rclpy's message info, as `topic echo -i` prints it: the publish time is the
        source timestamp, the log (receive) time the received one; no sequence numbers are
        kept in a bag."""
        return {
            "source_timestamp": self.stamp(publish_time),
            "received_timestamp": self.stamp(log_time),
            "publication_sequence_number": 0,
            "reception_sequence_number": 0,
        }

    def render(self, topic: str, value: object, log_time: int, publish_time: int) -> str | None:
        """The text of one message, or None when `--filter` drops it."""
        from ros2lite.interfaces.classes import Message

        if isinstance(value, (bytes, bytearray)) and not self.raw:
            if topic not in self.undecoded:
                self.undecoded.add(topic)
                warn(
                    f"Cannot decode the messages of '{topic}' (its type is neither known here "
                    "nor defined in the bag): printed as raw CDR"
                )
        elif self.field is not None:
            parent = value
            for name in self.field:
                parent = value
                try:
                    value = getattr(value, name)
                except AttributeError as e:
                    raise CliError(f"Invalid field '{'.'.join(self.field)}': {e}") from None
            if self.json and topic not in self.field_types:
                from ros2lite.interfaces.convert import field_type

                self.field_types[topic] = field_type(parent, self.field[-1])
        if self.filter_fn is not None and not self.filter_fn(value):
            return None
        if self.json:
            return self._json(topic, value, log_time, publish_time)
        info = self.info(log_time, publish_time)
        if not isinstance(value, Message):
            head = ""
            if self.headers:
                head = f"# {topic} {self.when(log_time)}\n"
            if self.include_info:
                head += f"---Got new message, message info:---\n{info}\n---Message data:---\n"
            return f"{head}{value}\n---\n"
        fmt = self.fmt
        opts = {
            "truncate_length": fmt["truncate_length"],
            "no_arr": fmt["no_arr"],
            "no_str": fmt["no_str"],
        }
        if fmt["csv"]:
            from ros2lite.interfaces import message_to_csv

            text = message_to_csv(value, **opts)  # type: ignore[arg-type]
            if self.include_info:
                text = ",".join(str(v) for v in info.values()) + "," + text
            if self.headers:
                text = f"{topic},{self.when(log_time)},{text}"
            return text + "\n"
        from ros2lite.interfaces import message_to_yaml

        head = f"# {topic} {self.when(log_time)}\n" if self.headers else ""
        if self.include_info:
            head += "".join(f"{k}: {v}\n" for k, v in sorted(info.items())) + "---\n"
        return head + message_to_yaml(value, flow_style=fmt["flow_style"], **opts) + "---\n"  # type: ignore[arg-type]

    def _json(self, topic: str, value: object, log_time: int, publish_time: int) -> str:
        """`topic echo --json`'s line for the message (`--raw` or an undecodable type: the
        CDR bytes as one base64 string), in the `"topic"` wrapper when several are echoed."""
        from ros2lite.interfaces.json_form import dumps, echo_record, value_to_json

        body = value_to_json(  # bytes (raw CDR) become one base64 string
            value, self.field_types.get(topic), no_arr=self.fmt["no_arr"], no_str=self.fmt["no_str"]
        )
        info = self.info(log_time, publish_time) if self.include_info or self.headers else None
        return dumps(echo_record(body, info, topic if self.headers else None)) + "\n"


@command("echo")
@click.argument("bag_path", type=click.Path())
@click.argument("topics", nargs=-1)
@format_options(
    csv_help=f"{CSV_HELP}. With several topics each row starts with the topic and log time.",
    after_csv=[
        click.option(
            "--json",
            "as_json",
            is_flag=True,
            help='topic echo --json\'s lines (NDJSON; -i: {"message", "info"}); with several '
            'topics {"topic", "message", "info"}.',
        ),
        click.option(
            "--field",
            help="Echo a selected field of a message; use '.' to select sub-fields "
            "(e.g. 'pose.pose.position')",
        ),
    ],
)
@click.option("--start", metavar="T", help=f"First time printed: {TIME_HELP}.")
@click.option("--end", metavar="T", help="Last time printed (included).")
@click.option("--raw", is_flag=True, help="Echo the raw binary representation")
@click.option(
    "--filter",
    "filter_expr",
    metavar="EXPR",
    help="Python expression to filter the messages printed; it can use Python builtins and m "
    "(the message)",
)
@click.option("-n", "--count", type=click.IntRange(min=1), help="Stop after printing N messages.")
@click.option(
    "-i", "--include-message-info", is_flag=True, help="Shows the associated message info"
)
@click.option("--human", is_flag=True, help="Print times as local dates, not sec.nanosec.")
def cli(
    bag_path: str,
    topics: tuple[str, ...],
    fmt: MessageFormat,
    as_json: bool,
    field: str | None,
    start: str | None,
    end: str | None,
    raw: bool,
    filter_expr: str | None,
    count: int | None,
    include_message_info: bool,
    human: bool,
) -> None:
    """Print the messages of a bag, as `topic echo` prints them."""
    from ros2lite.bag import Reader
    from ros2lite.bag.cut import parse_time
    from ros2lite.bag.errors import BagError

    fields: list[str] | None = None
    if field is not None:
        fields = [f for f in field.split(".") if f]
        if not fields:
            raise CliError(f"Invalid field value '{field}'")
    if as_json and fmt["csv"]:
        raise CliError("--json and --csv cannot be combined")
    filter_fn = compile_filter(filter_expr)
    out = sys.stdout
    try:
        with Reader(bag_path) as reader:
            names = [t.name for t in reader.topics]
            chosen: list[str] = []
            for t in topics:
                name = t if t in names or t.startswith("/") else "/" + t
                if name not in names:
                    raise bag_error(f"The bag has no topic '{t}'")
                chosen.append(name)
            origin = reader.start_time if reader.message_count else 0
            begin = None if start is None else parse_time(start, origin)
            finish = None if end is None else parse_time(end, origin) + 1
            printer = BagPrinter(
                fmt,
                json=as_json,
                raw=raw,
                field=fields,
                filter_fn=filter_fn,
                include_info=include_message_info,
                human=human,
                headers=len(chosen or names) > 1,
            )
            printed = 0
            wanted = chosen or None
            decode = not raw
            for topic, data, log_time, publish_time in reader.raw_messages(wanted, begin, finish):
                value: object = reader.decode(topic, data) if decode else data
                text = printer.render(topic, value, log_time, publish_time)
                if text is None:
                    continue
                out.write(text)
                printed += 1
                if count is not None and printed >= count:
                    break
    except BagError as e:
        raise bag_error(str(e)) from None
    except BrokenPipeError:
        sys.stderr.close()  # `| head`: the reader left, nothing more to say
