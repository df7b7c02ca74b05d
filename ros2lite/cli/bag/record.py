"""`bag record`: record topics into a rosbag2 MCAP bag until Ctrl-C (or SIGTERM).

The library's Recorder does the work (raw subscriptions, a writer thread, clean close); this
verb parses ros2cli's options, logs rosbag2_recorder's lines on stderr and, on a terminal,
keeps a live per-topic status and takes SPACE to pause/resume.
"""

from __future__ import annotations

import dataclasses
import os
import time
from typing import TYPE_CHECKING

import click

from ros2lite.util import keyboard as keys_module

from .. import completion, numbers, render
from ..common import connect
from ..options import bind
from ..parsing import ManyValues, command
from .options import (
    bag_error,
    check_patterns,
    qos_overrides,
    record_options,
    services_option,
    shared_options,
    storage_option,
    topics_option,
    warn,
)

if TYPE_CHECKING:
    from collections.abc import Callable

    from ros2lite.bag.recorder import Recorder, RecordOptions
    from ros2lite.bag.writer import Writer
    from ros2lite.logging import RcutilsLogger
    from ros2lite.node import Node
    from ros2lite.tools.connection import Connection

SELECTION_ERROR = (
    "Need to specify at least one option out of --all, --all-topics, "
    "--all-services, --services, --topics, --topic-types or --regex"
)


@command("record")
@click.argument(
    "positional_topics", metavar="[TOPICS]...", nargs=-1, shell_complete=completion.topics
)
@topics_option("List of topics to record.")
@services_option("List of services to record (their service-event topics).")
@click.option(
    "--topic-types", cls=ManyValues, metavar="TYPE...", help="Record topics of these types."
)
@click.option(
    "--exclude-topic-types",
    cls=ManyValues,
    metavar="TYPE...",
    help="Do not record topics of these types.",
)
@shared_options("record", "offered")
@click.option("-a", "--all", "all_", is_flag=True, help="Record all topics and services.")
@click.option("--all-topics", is_flag=True, help="Record all topics (no services).")
@click.option("--all-services", is_flag=True, help="Record all services.")
@click.option(
    "--exclude-services",
    cls=ManyValues,
    metavar="SERVICE...",
    help="List of services not to record.",
)
@click.option(
    "--include-hidden-topics",
    is_flag=True,
    help="Record hidden topics as well (names with a part starting with _).",
)
@click.option(
    "-o",
    "--output",
    metavar="URI",
    help="Destination of the bag (default rosbag2_<local date and time>).",
)
@storage_option("Storage identifier.", default="mcap")
@click.option(
    "-b",
    "--max-bag-size",
    type=numbers.Count(min=0, max=2**63 - 1),
    default=0,
    help="Split the bag at this many bytes (0: no splitting).",
)
@click.option(
    "-d",
    "--max-bag-duration",
    type=numbers.seconds(),
    default=0,
    help="Split the bag after this many seconds (0: no splitting).",
)
@click.option(
    "--max-cache-size",
    type=numbers.Count(min=0, max=2**63 - 1),
    default=100 * 1024 * 1024,
    show_default=True,
    help="Bytes per topic kept in memory while the disk catches up; past it the "
    "receiver waits (Zenoh then queues) rather than dropping messages.",
)
@click.option(
    "--snapshot",
    "snapshot_duration",
    type=numbers.seconds(min_open=True),
    metavar="DURATION",
    help="Snapshot mode: keep the last DURATION seconds in memory (at most --max-cache-size "
    "bytes) and write them only when the ~/snapshot service is called or on SIGUSR1.",
)
@click.option(
    "--snapshot-mode",
    is_flag=True,
    help="rosbag2's snapshot mode: the buffer is bounded by --max-cache-size alone.",
)
@click.option(
    "--storage-preset-profile",
    type=click.Choice(["none", "fastwrite", "zstd_fast", "zstd_small"]),
    help="MCAP preset: zstd_fast / zstd_small compress chunks.",
)
@click.option(
    "--compression-mode",
    type=click.Choice(["none", "file", "message"]),
    default="none",
    help='Only "none": MCAP bags compress chunks instead.',
)
@click.option(
    "--compression-format",
    type=click.Choice(["zstd", "lz4"]),
    help="Compress MCAP chunks with this format (the bag stays indexed).",
)
@click.option("--use-sim-time", is_flag=True, help="Stamp messages with /clock time.")
@click.option(
    "--no-discovery", is_flag=True, help="Subscribe only to topics that exist at start-up."
)
@click.option(
    "-p",
    "--polling-interval",
    "polling_interval_ms",
    type=numbers.Count(min=1, max=3_600_000),
    default=100,
    show_default=True,
    help="Milliseconds between topic discovery passes.",
)
@click.option(
    "--flush-interval",
    "flush_interval_ms",
    type=numbers.Count(min=1, max=3_600_000),
    default=100,
    show_default=True,
    metavar="MS",
    help="Milliseconds a received message may wait in memory before its chunk is written: "
    "what a recorder killed outright (SIGKILL, power loss) can lose at most.",
)
@click.option(
    "--node-name", default="rosbag2_recorder", show_default=True, help="Name of the recorder node."
)
@click.option(
    "--custom-data",
    cls=ManyValues,
    metavar="KEY=VALUE...",
    help="Custom metadata stored in the bag.",
)
@bind(record_options)
def cli(
    options: RecordOptions,
    positional_topics: tuple[str, ...],
    services: tuple[str, ...],
    all_: bool,
    exclude_services: tuple[str, ...],
    output: str | None,
    storage: str,
    max_bag_size: int,
    max_bag_duration: float,
    storage_preset_profile: str | None,
    compression_mode: str,
    compression_format: str | None,
    qos_profile_overrides_path: str | None,
    use_sim_time: bool,
    no_discovery: bool,
    polling_interval_ms: int,
    flush_interval_ms: int,
    node_name: str,
    custom_data: tuple[str, ...],
    disable_keyboard_controls: bool,
    snapshot_duration: float | None,
    snapshot_mode: bool,
) -> None:
    """Record ROS data to a bag."""

    from ros2lite.bag.errors import BagError
    from ros2lite.bag.writer import Writer

    if positional_topics:
        warn(
            'Positional "topics" argument deprecated. Please use optional "--topics" '
            "argument instead."
        )
    selected = list(positional_topics) + options.topics
    if not (
        selected
        or services
        or options.topic_types
        or all_
        or options.all_topics
        or options.all_services
        or options.regex
    ):
        raise bag_error(SELECTION_ERROR)
    check_patterns(options.regex, options.exclude_regex)
    if storage != "mcap":
        raise bag_error(f"Recording to '{storage}' is not supported; use -s mcap")
    if compression_mode != "none":
        raise bag_error(
            f"Compression mode '{compression_mode}' is not supported for MCAP; "
            f"use --compression-format alone (chunk compression)"
        )
    from ros2lite.service_introspection import event_topic

    events = [event_topic(s) for s in services]
    excluded_events = [event_topic(s) for s in exclude_services]
    options = dataclasses.replace(
        options,
        topics=list(dict.fromkeys(_absolute(selected + events, node_name))),
        all_topics=all_ or options.all_topics,
        all_services=all_ or options.all_services,
        exclude_topics=_absolute(options.exclude_topics + excluded_events, node_name),
        qos_overrides=qos_overrides(qos_profile_overrides_path),
        polling_interval=polling_interval_ms / 1000,
        discovery=not no_discovery,
        flush_interval=flush_interval_ms / 1000,
    )
    custom = _custom_data(custom_data)
    uri = output or time.strftime("rosbag2_%Y_%m_%d-%H_%M_%S")
    if os.path.exists(uri):
        raise bag_error(f"Output folder '{uri}' already exists.")
    try:
        if snapshot_duration is not None or snapshot_mode:
            writer = _snapshot_writer(
                uri,
                snapshot_duration or 0.0,
                options.max_cache_size,
                split=bool(max_bag_size or max_bag_duration),
                compression=compression_format or "none",
                preset=storage_preset_profile,
                custom_data=custom,
            )
        else:
            writer = Writer(
                uri,
                compression=compression_format or "none",
                preset=storage_preset_profile,
                max_bag_size=max_bag_size,
                max_bag_duration=max_bag_duration,
                custom_data=custom,
            ).open()
    except BagError as e:
        raise bag_error(str(e)) from None
    # the recorder is a node: a peer session keeps it hearing publishers through a router outage
    conn = connect(use_sim_time=use_sim_time, as_node=True)
    try:
        conn.open()
    except BaseException:
        writer.discard()  # no graph to record from: leave nothing behind
        raise
    with conn:
        recorder = _record(conn, writer, options, node_name, keyboard=not disable_keyboard_controls)
    if recorder.error is not None:
        raise bag_error(
            f"{recorder.error}. Messages written before this are kept in "
            f"'{uri}' (run `ros2lite bag reindex {uri}` if another tool "
            f"cannot open it)"
        )


def _snapshot_writer(
    uri: str, duration: float, max_bytes: int, *, split: bool, **options: object
) -> Writer:
    """The bag of snapshot mode (a file per snapshot, so no size or time splits)."""
    from ros2lite.bag.snapshot import SnapshotWriter

    if split:
        raise bag_error("--max-bag-size and --max-bag-duration do not apply to snapshots")
    return SnapshotWriter(uri, duration=duration, max_bytes=max_bytes, **options).open()


def _serve_snapshots(
    conn: Connection, node: Node, recorder: Recorder, log: RcutilsLogger
) -> tuple[Callable[[], object], Callable[[], object]]:
    """The ~/snapshot service on the recorder node, and SIGUSR1: both ask for a snapshot.
    Returns what SIGUSR1 runs and what the main loop runs to serve it."""
    import threading

    from ros2lite.bag.snapshot import SnapshotWriter, snapshot_handler
    from ros2lite.msgs.rosbag2_interfaces.srv import Snapshot, Snapshot_Response

    writer = recorder.writer
    assert isinstance(writer, SnapshotWriter)
    clock = node.get_clock()
    trigger = snapshot_handler(
        recorder, writer, lambda: clock.now().nanoseconds, lambda m: log.info(m)
    )

    def serve(request: object, response: Snapshot_Response) -> Snapshot_Response:
        response.success = trigger()
        return response

    node.create_service(Snapshot, "~/snapshot", serve)
    asked = threading.Event()
    log.info(f"Snapshot mode: call {node.get_fully_qualified_name()}/snapshot or send SIGUSR1")

    def on_tick() -> None:
        if asked.is_set():
            asked.clear()
            trigger()

    return asked.set, on_tick


def _absolute(names: list[str], node_name: str) -> list[str]:
    """Topic names as the recorder node resolves them (it lives in the root namespace)."""
    from ros2lite.names import expand_topic_name

    try:
        return [expand_topic_name(n, node_name, "/") for n in names]
    except ValueError as e:
        raise bag_error(str(e)) from None


def _custom_data(pairs: tuple[str, ...]) -> dict[str, str] | None:
    out = {}
    for pair in pairs:
        key, sep, value = pair.partition("=")
        if not sep or not key:
            raise bag_error(f"Custom data '{pair}' is not KEY=VALUE")
        out[key] = value
    return out or None


def _record(
    conn: Connection,
    writer: Writer,
    options: RecordOptions,
    node_name: str,
    keyboard: bool,
) -> Recorder:
    """Run the recorder until a signal (or a write error); returns it, stopped."""
    from ros2lite.bag.recorder import Recorder
    from ros2lite.logging import get_logger
    from ros2lite.util.process import StopSignals, on_signals

    log = get_logger(node_name)
    node = conn.node(node_name)
    recorder = Recorder(
        node, writer, options, log=lambda m: log.info(m), warn=lambda m: log.warn(m)
    )
    status = _LiveStatus(recorder) if render.fancy() else None
    keys = None
    if keyboard and keys_module.available():
        log.info("Press SPACE for pausing/resuming")
        keys = keys_module.KeyHandlers({" ": recorder.toggle_paused})
    ticks: list[Callable[[], object]] = [status.update] if status is not None else []
    signals: dict[int, Callable[[], object]] = {}
    snapshots = getattr(writer, "snapshot", None) is not None
    if snapshots:
        import signal

        ask, serve = _serve_snapshots(conn, node, recorder, log)
        signals[signal.SIGUSR1] = ask
        ticks.append(serve)
    try:
        with StopSignals() as stop, on_signals(signals):
            recorder.run(
                stop.event,
                # the snapshot service's calls are served by spinning the node
                spin=(lambda t: conn.spin_until(timeout=t))
                if conn.use_sim_time or snapshots
                else None,
                on_tick=(lambda: [tick() for tick in ticks]) if ticks else None,
            )
    finally:
        if keys is not None:
            keys.close()
        if status is not None:
            status.close()
    return recorder


class _LiveStatus:
    """Per-topic count, bytes and rate, redrawn in place on a terminal."""

    def __init__(self, recorder: Recorder) -> None:
        self.recorder = recorder
        self._last: dict[str, tuple[float, int]] = {}
        self._rates: dict[str, float] = {}
        self._table = render.LiveTable(
            ("topic", "type", "messages", "size", "rate"), transient=True
        )

    def update(self) -> None:
        now = time.monotonic()
        rows = []
        for s in list(self.recorder.stats):
            then, count = self._last.get(s.name, (now, s.received))
            if now - then >= 1.0:
                self._rates[s.name] = (s.received - count) / (now - then)
                self._last[s.name] = (now, s.received)
            else:
                self._last.setdefault(s.name, (now, s.received))
            rows.append(
                (
                    s.name,
                    s.type,
                    str(s.received),
                    render.format_size(s.bytes),
                    f"{self._rates.get(s.name, 0.0):.1f} Hz",
                )
            )
        self._table.show(rows, title="Paused" if self.recorder.paused else "Recording")

    def close(self) -> None:
        self._table.close()
