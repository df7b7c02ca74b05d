"""`bag info`: rosbag2's summary of a bag, laid out exactly as `ros2 bag info` prints it.

Only metadata.yaml (or, without one, each file's MCAP summary section) is read, so the answer
takes the same time for a 1 KiB and a 100 GiB bag; `-v` also reads the messages to sum each
topic's size.
"""

from __future__ import annotations

import os
import time
from pathlib import Path
from typing import TYPE_CHECKING

import click

from ros2lite.service_introspection import EVENT_TOPIC_SUFFIX as SERVICE_EVENT_SUFFIX

from ..options import json_option
from ..parsing import command
from ..render import echo as echo_shown
from ..render import format_size, print_json
from .options import bag_argument, bag_error, existing_bag, warn

if TYPE_CHECKING:
    from ros2lite.bag.metadata import TopicInformation
    from ros2lite.bag.reader import Reader

LABEL = 19


def format_time(ns: int) -> str:
    """Local `%b %e %Y %H:%M:%S.<ns>` and `(sec.nsec)`, as rosbag2 prints a time point."""
    sec, nsec = divmod(ns, 1_000_000_000)
    try:
        local = time.strftime("%b %e %Y %H:%M:%S", time.localtime(sec))
    except (OverflowError, OSError, ValueError):
        local = "?"
    return f"{local}.{nsec:09d} ({sec}.{nsec:09d})"


def format_duration(ns: int) -> str:
    sec, nsec = divmod(ns, 1_000_000_000)
    return f"{sec}.{nsec:09d}s"


def bag_size(path: Path) -> int:
    if path.is_file():
        return path.stat().st_size
    total = 0
    for entry in os.scandir(path):
        if entry.is_file():
            total += entry.stat().st_size
    return total


def _lines(label: str, items: list[str], indent: int = LABEL) -> list[str]:
    if not items:
        return [label]
    return [label + items[0]] + [" " * indent + item for item in items[1:]]


def _topics_and_services(
    reader: Reader, sort: str
) -> tuple[list[TopicInformation], list[TopicInformation]]:
    """The bag's topics and its service-event topics, each in the order `--sort` asks."""
    m = reader.metadata
    topics = [
        t
        for t in m.topics_with_message_count
        if not t.topic_metadata.name.endswith(SERVICE_EVENT_SUFFIX)
    ]
    services = [
        t
        for t in m.topics_with_message_count
        if t.topic_metadata.name.endswith(SERVICE_EVENT_SUFFIX)
    ]
    keys = {
        "name": lambda t: t.topic_metadata.name,
        "type": lambda t: t.topic_metadata.type,
        "count": lambda t: t.message_count,
    }
    topics.sort(key=keys[sort])
    services.sort(key=keys[sort])
    return topics, services


def info_json(
    path: Path, reader: Reader, *, sort: str, sizes: dict[str, int] | None
) -> dict[str, object]:
    """`bag info --json`: the summary as data (times and durations in integer nanoseconds,
    sizes in bytes; "size" per topic only with -v)."""
    m = reader.metadata
    topics, services = _topics_and_services(reader, sort)

    def size(name: str) -> dict[str, object]:
        return {} if sizes is None else {"size": sizes.get(name, 0)}

    return {
        "files": [f.name for f in reader.files],
        "bag_size": bag_size(path),
        "storage_identifier": m.storage_identifier,
        "ros_distro": m.ros_distro,
        "duration_ns": m.duration,
        "starting_time_ns": m.starting_time,
        "end_time_ns": m.starting_time + m.duration,
        "message_count": sum(t.message_count for t in topics),
        "topics": [
            {
                "name": t.topic_metadata.name,
                "type": t.topic_metadata.type,
                "message_count": t.message_count,
                "serialization_format": t.topic_metadata.serialization_format,
                **size(t.topic_metadata.name),
            }
            for t in topics
        ],
        "services": [
            {
                "name": s.topic_metadata.name[: -len(SERVICE_EVENT_SUFFIX)],
                "type": s.topic_metadata.type.removesuffix("_Event"),
                "event_count": s.message_count,
                "serialization_format": s.topic_metadata.serialization_format,
                **size(s.topic_metadata.name),
            }
            for s in services
        ],
    }


def render(
    path: Path, reader: Reader, *, verbose: bool, sort: str, sizes: dict[str, int] | None
) -> str:
    m = reader.metadata
    topics, services = _topics_and_services(reader, sort)
    messages = sum(t.message_count for t in topics)

    def size_part(name: str) -> str:
        if sizes is None:
            return ""
        return f"Size Contribution: {format_size(sizes.get(name, 0))} | "

    topic_items = [
        f"Topic: {t.topic_metadata.name} | Type: {t.topic_metadata.type} | "
        f"Count: {t.message_count} | {size_part(t.topic_metadata.name)}"
        f"Serialization Format: {t.topic_metadata.serialization_format}"
        for t in topics
    ]
    service_items = []
    for s in services:
        name = s.topic_metadata.name[: -len(SERVICE_EVENT_SUFFIX)]
        type_name = s.topic_metadata.type.removesuffix("_Event")
        service_items.append(
            f"Service: {name} | Type: {type_name} | Event Count: {s.message_count} | "
            f"{size_part(s.topic_metadata.name)}"
            f"Serialization Format: {s.topic_metadata.serialization_format}"
        )
    files = [f.name for f in reader.files]
    out = ["", *_lines("Files:".ljust(LABEL), files)]
    out += [
        "Bag size:".ljust(LABEL) + format_size(bag_size(path)),
        "Storage id:".ljust(LABEL) + m.storage_identifier,
        "ROS Distro:".ljust(LABEL) + m.ros_distro,
        "Duration:".ljust(LABEL) + format_duration(m.duration),
        "Start:".ljust(LABEL) + format_time(m.starting_time),
        "End:".ljust(LABEL) + format_time(m.starting_time + m.duration),
        "Messages:".ljust(LABEL) + str(messages),
    ]
    out += _lines("Topic information: ", topic_items)
    out.append("Service:".ljust(LABEL) + str(len(services)))
    out += _lines("Service information: ", service_items, indent=21)
    return "\n".join(out) + "\n"


def message_sizes(reader: Reader) -> dict[str, int]:
    sizes: dict[str, int] = {}
    for topic, data, _log, _pub in reader.raw_messages():
        sizes[topic] = sizes.get(topic, 0) + len(data)
    return sizes


@command("info")
@bag_argument
@click.option("-t", "--topic-name", is_flag=True, help="Only print topic names.")
@click.option(
    "-v",
    "--verbose",
    is_flag=True,
    help="Also print the size each topic contributes (reads every message).",
)
@click.option(
    "--sort",
    type=click.Choice(["name", "type", "count"]),
    default="name",
    show_default=True,
    help="Order of the topic list.",
)
@json_option('the summary: {"files", "bag_size", "duration_ns", …, "topics", "services"}')
def cli(
    bag_path: str, storage: str | None, topic_name: bool, verbose: bool, sort: str, as_json: bool
) -> None:
    """Print information about a bag to the screen."""
    from ros2lite.bag.errors import BagError
    from ros2lite.bag.reader import Reader

    path = existing_bag(bag_path)
    if topic_name and verbose:
        warn(
            "Warning! You have set both the '-t' and '-v' parameters. The '-t' parameter "
            "will be ignored."
        )
        topic_name = False
    try:
        with Reader(path, storage) as reader:
            if topic_name:
                names = sorted(t.name for t in reader.topics)
                if as_json:
                    print_json(names)
                    return
                echo_shown("".join(n + "\n" for n in names), nl=False)
                return
            sizes = message_sizes(reader) if verbose else None
            for problem in reader.shortfalls():
                warn(problem)
            if as_json:
                print_json(info_json(path, reader, sort=sort, sizes=sizes))
                return
            echo_shown(render(path, reader, verbose=verbose, sort=sort, sizes=sizes), nl=False)
    except BagError as e:
        raise bag_error(str(e)) from None
