"""Recording: subscribe raw to the selected topics and write every sample into a bag.

Samples are never decoded. Each subscription's receive thread only appends
`(topic, bytes, received, attachment)` to one queue; a writer thread of our own drains it into
the bag, so a slow disk never makes a subscriber miss a sample. The queue is bounded per topic
by `max_cache_size` bytes: past it the receive thread waits, which pushes back through Zenoh
(subscriptions are KEEP_ALL, so Zenoh queues instead of dropping) rather than losing data.
`stop()` drains the queue, finishes the file and writes metadata.yaml: nothing received is
lost.

Discovery polls the node's live graph: topics that appear while recording are picked up,
with the QoS every publisher offers (TRANSIENT_LOCAL included, so latched samples arrive).
"""

from __future__ import annotations

import contextlib
import re
import threading
import time
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ros2lite.bag.errors import BagError
from ros2lite.bag.writer import Writer
from ros2lite.context import RouterLink
from ros2lite.qos import QoSProfile
from ros2lite.service_introspection import EVENT_TOPIC_SUFFIX as SERVICE_EVENT_SUFFIX
from ros2lite.transport.attachment import source_timestamp

if TYPE_CHECKING:
    from ros2lite.graph import Entity
    from ros2lite.monitor.subscription import MonitoredSubscription
    from ros2lite.node import Node

__all__ = [
    "DEFAULT_FLUSH_INTERVAL",
    "DEFAULT_MAX_CACHE_SIZE",
    "RecordOptions",
    "Recorder",
    "TopicStats",
]

DEFAULT_MAX_CACHE_SIZE = 100 * 1024 * 1024
# how long received messages may wait in memory before the chunk holding them is put on disk
# anyway (seconds): what a recorder killed outright (SIGKILL, power loss) can lose at most
DEFAULT_FLUSH_INTERVAL = 0.1
# how often the writer looks at the clock while busy (messages)
_CLOCK_EVERY = 64
# how often the router link is looked at (seconds)
_ROUTER_CHECK_PERIOD = 1.0


@dataclass
class RecordOptions:
    """What to record; the fields mirror `ros2 bag record`'s options."""

    topics: list[str] = field(default_factory=list)  # fully qualified names
    all_topics: bool = False
    all_services: bool = False  # service-event topics (`<service>/_service_event`)
    regex: str | None = None
    exclude_regex: str | None = None
    exclude_topics: list[str] = field(default_factory=list)
    topic_types: list[str] = field(default_factory=list)
    exclude_topic_types: list[str] = field(default_factory=list)
    include_hidden_topics: bool = False
    qos_overrides: dict[str, QoSProfile] = field(default_factory=dict)
    polling_interval: float = 0.1
    max_cache_size: int = DEFAULT_MAX_CACHE_SIZE
    start_paused: bool = False
    discovery: bool = True  # keep looking for new topics while recording
    flush_interval: float = DEFAULT_FLUSH_INTERVAL  # seconds a message may wait for the disk

    def selects_by_pattern(self) -> bool:
        """Whether topics are chosen by a rule (all, regex, types) rather than by name."""
        return self.all_topics or self.all_services or bool(self.regex) or bool(self.topic_types)

    def selects(self, topic: str, type_name: str) -> bool:
        """Whether these options ask for `topic` of this type (the recorder's and `bag
        convert`'s one rule: excludes first, then names, service events, hidden, patterns)."""
        if (
            topic in self.exclude_topics
            or type_name in self.exclude_topic_types
            or (self.exclude_regex and re.search(self.exclude_regex, topic))
        ):
            return False
        if topic in self.topics:
            return True
        if topic.endswith(SERVICE_EVENT_SUFFIX):
            return self.all_services or bool(self.regex and re.search(self.regex, topic))
        if not self.include_hidden_topics:
            from ros2lite.names import is_hidden_name

            if is_hidden_name(topic):
                return False
        if self.all_topics:
            return True
        if self.regex and re.search(self.regex, topic):
            return True
        return type_name in self.topic_types


@dataclass
class TopicStats:
    """Per-topic counters the status display reads (written by one receive thread each)."""

    name: str
    type: str
    received: int = 0
    bytes: int = 0
    written_bytes: int = 0


class Recorder:
    """Records topics of the graph `node` sees into `writer` until `stop()`.

    `log(message)` receives rosbag2_recorder's info lines ("Subscribed to topic '/x'", …);
    `error` holds the failure that ended recording early (a full disk), if any.
    """

    def __init__(
        self,
        node: Node,
        writer: Writer,
        options: RecordOptions,
        *,
        log: Callable[[str], object] | None = None,
        warn: Callable[[str], object] | None = None,
    ) -> None:
        self.node = node
        self.writer = writer
        self.options = options
        self._log = log or (lambda _m: None)
        self._warn = warn or self._log
        self._clock = node.get_clock()
        self.stats: list[TopicStats] = []
        self._stats_by_tid: dict[int, TopicStats] = {}
        self._by_name: dict[str, int] = {}
        self._skipped: set[str] = set()
        self._subscriptions: list[MonitoredSubscription] = []
        self._queue: deque[tuple[int, bytes, int, bytes]] = deque()
        self._wake = threading.Event()
        self._writer_idle = False
        self._paused = options.start_paused
        self._running = False
        self._stopping = False
        self._lock = threading.Lock()  # subscribe vs stop
        self._writer_thread: threading.Thread | None = None
        self._discovery_thread: threading.Thread | None = None
        self._discovery_done = threading.Event()
        self.error: BaseException | None = None
        self._router = RouterLink(node.context, self._router_changed)
        self._router_checked = 0.0

    # -- control -------------------------------------------------------------------------------
    def start(self) -> None:
        """Open the bag, subscribe to what is wanted now and (with discovery) keep looking."""
        self._running = True
        self.writer.open()
        self._writer_thread = threading.Thread(
            target=self._write_loop, daemon=True, name="ros2lite-bag-writer"
        )
        self._writer_thread.start()
        if self.options.start_paused:
            self._log("Wait for recording: Press SPACE to start.")
        self._log("Listening for topics...")
        self.discover()
        if self.options.discovery:
            self._discovery_thread = threading.Thread(
                target=self._discovery_loop, daemon=True, name="ros2lite-bag-discovery"
            )
            self._discovery_thread.start()
        self._log("Recording...")

    @property
    def paused(self) -> bool:
        """Whether recording is paused (messages are dropped meanwhile)."""
        return self._paused

    def pause(self) -> None:
        """Stop writing messages until resume()."""
        if not self._paused:
            self._paused = True
            self._log("Pausing recording.")

    def resume(self) -> None:
        """Write messages again."""
        if self._paused:
            self._paused = False
            self._log("Resuming recording.")

    def toggle_paused(self) -> None:
        """Pause or resume, as the space key does."""
        if self._paused:
            self.resume()
        else:
            self.pause()

    @property
    def running(self) -> bool:
        """False once stopped, or once a write error ended recording."""
        return self._running and self.error is None

    def run(
        self,
        stop: threading.Event,
        *,
        spin: Callable[[float], object] | None = None,
        on_tick: Callable[[], object] | None = None,
    ) -> None:
        """Record until `stop` is set (a signal), recording fails or the context ends; the
        bag is always finished. `spin(seconds)` runs the node's callbacks for up to that long:
        needed under sim time, where recording starts with the first /clock."""
        from ros2lite.logging import get_logger

        clock = self.node.get_clock()
        try:
            if spin is not None and clock.ros_time_is_active:
                self._log("use_sim_time set, waiting for /clock before starting recording...")
                while clock.now().nanoseconds == 0 and not stop.is_set():
                    spin(0.1)
            if stop.is_set():
                return
            self.start()
            while not stop.is_set() and self.running and self.node.context.ok():
                if spin is not None:
                    spin(0.25)
                else:
                    stop.wait(0.25)
                self._watch_router()
                if on_tick is not None:
                    on_tick()
        finally:
            get_logger("rosbag2_cpp").info(
                "Writing remaining messages from cache to the bag. It may take a while"
            )
            self.stop()
            self._log("Recording stopped")

    def _watch_router(self) -> None:
        """Say when the graph becomes unreachable (no router) and when it is back. Recording
        goes on meanwhile: the node's peer session still hears every publisher it has met."""
        now = time.monotonic()
        if now - self._router_checked < _ROUTER_CHECK_PERIOD:
            return
        self._router_checked = now
        self._router.check()

    def _router_changed(self, connected: bool) -> None:
        if connected:
            self._log("The Zenoh router is back: topics that appear are picked up again.")
        else:
            self._warn(
                "The graph is unreachable: no Zenoh router answers. Still recording the "
                "publishers this node already hears (peer to peer); new topics are picked up "
                "when a router answers again."
            )

    def queued(self) -> int:
        """Messages received and not written yet."""
        return len(self._queue)

    def stop(self) -> None:
        """Stop receiving, write everything received, finish the bag. Idempotent."""
        with self._lock:
            if self._stopping:
                return
            self._stopping = True  # no new subscriptions from here on
        self._discovery_done.set()
        if self._discovery_thread is not None:
            self._discovery_thread.join(timeout=5)
        # samples keep being queued until each subscription is gone (its receive thread is
        # joined), so everything that reached this process gets written
        for sub in self._subscriptions:
            # the session may be gone already: then nothing more arrives anyway
            with contextlib.suppress(Exception):
                sub.destroy()
        self._running = False
        self._wake.set()
        if self._writer_thread is not None:
            self._writer_thread.join()
        if self.error is None:
            try:
                self.writer.close()
            except (BagError, OSError) as e:
                self.error = e
                self.writer.abandon()
        else:
            self.writer.abandon()

    # -- discovery -----------------------------------------------------------------------------
    def _discovery_loop(self) -> None:
        interval = max(self.options.polling_interval, 0.01)
        while not self._discovery_done.wait(interval):
            try:
                self.discover()
            except Exception as e:  # the graph went away with the session: stop looking
                if not self._stopping:
                    self._warn(f"Topic discovery failed: {e}")
                return
            if (
                self.options.topics
                and not self.options.selects_by_pattern()
                and all(t in self._by_name or t in self._skipped for t in self.options.topics)
            ):
                self._log("All requested topics are subscribed. Stopping discovery...")
                return

    def wanted(self, topic: str, type_name: str) -> bool:
        """Whether the options ask for `topic` of this type."""
        return self.options.selects(topic, type_name)

    def discover(self) -> None:
        """Subscribe to every wanted topic that has publishers and no subscription yet."""
        from ros2lite.transport.keys import EntityKind

        publishers: dict[str, list[Entity]] = {}
        for e in self.node.context.graph.entities():
            if e.kind == EntityKind.PUBLISHER and e.topic_name and e.type_name:
                publishers.setdefault(e.topic_name, []).append(e)
        for topic, pubs in sorted(publishers.items()):
            if topic in self._by_name or topic in self._skipped:
                continue
            types = sorted({p.type_name or '' for p in pubs})  # (all named: see above)
            if not any(self.wanted(topic, t) for t in types):
                continue
            if len(types) > 1:
                self._skipped.add(topic)
                self._warn(
                    f"Topic '{topic}' has more than one type ({', '.join(types)}); not recording it"
                )
                continue
            self._subscribe(topic, types[0], pubs)

    def _subscribe(self, topic: str, type_name: str, pubs: list[Entity]) -> None:
        from ros2lite.bag.qos import recording_qos
        from ros2lite.interfaces import InterfaceError, get_interface
        from ros2lite.interfaces.parser import validate_type_name
        from ros2lite.monitor.subscription import MonitoredSubscription
        from ros2lite.names import validate_full_topic_name

        try:
            validate_full_topic_name(topic)
        except ValueError:  # a hostile or broken graph entry: skip it, record the others
            self._skipped.add(topic)
            self._warn(f"Not recording topic {topic!a}: not a valid topic name")
            return
        try:
            # the writer refuses it too, fatally: here it only skips this topic
            validate_type_name(type_name)
        except InterfaceError as e:
            self._skipped.add(topic)
            self._warn(f"Cannot record '{topic}': {e}")
            return
        offered = [p.qos for p in pubs if p.qos is not None]
        qos = self.options.qos_overrides.get(topic) or recording_qos(topic, offered, self._warn)
        hashes = {p.type_hash for p in pubs if p.type_hash}
        msg_type: type | str = type_name
        try:
            self._fetch_type(type_name, topic)
            get_interface(type_name)
        except (InterfaceError, LookupError, ValueError) as e:
            if len(hashes) != 1:
                self._skipped.add(topic)
                self._warn(f"Cannot record '{topic}': type {type_name} is unknown here ({e})")
                return
            # not defined here: record its bytes all the same, under the publishers' hash
            # (the bag gets an empty schema, as rosbag2 writes for unknown definitions)
            from ros2lite.bag.definitions import type_ref

            msg_type = type_ref(type_name, next(iter(hashes)))
        with self._lock:
            if self._stopping:
                return
            try:
                tid = self.writer.create_topic(
                    topic,
                    type_name,
                    offered_qos_profiles=offered,
                    type_description_hash=next(iter(hashes)) if len(hashes) == 1 else None,
                )
            except (BagError, OSError) as e:
                self._fail(e)
                return
            stats = self._stats_by_tid[tid] = TopicStats(topic, type_name)
            sub = MonitoredSubscription(
                self.node, msg_type, topic, None, qos, on_payload=self._receiver(tid, stats)
            )
            self.stats.append(stats)
            self._by_name[topic] = tid
            self._subscriptions.append(sub)
        self._log(f"Subscribed to topic '{topic}'")

    def _fetch_type(self, type_name: str, topic: str) -> None:
        """A type no local package defines, asked of a node that publishes it: the bag then
        gets its full definition as a schema, as for a local type."""
        from ros2lite.remote_types import RemoteTypeError, ensure_type

        try:
            ensure_type(lambda: self.node, self.node.context.graph.entities(), type_name, topic)
        except RemoteTypeError as e:  # its bytes are still recorded, with no schema
            self._warn(f"Topic '{topic}': {e}")

    def _receiver(self, tid: int, stats: TopicStats) -> Callable[[bytes, bytes, int], None]:
        """The per-sample hook, run on the subscription's receive thread: queue the bytes."""
        append, queue, wake = self._queue.append, self._queue, self._wake
        limit = max(self.options.max_cache_size, 1)
        clock = self._clock

        def receive(data: bytes, attachment: bytes, received: int) -> None:
            if self._paused:
                return
            if clock.ros_time_is_active:  # --use-sim-time and /clock is ticking
                received = clock.now().nanoseconds
            append((tid, data, received, attachment))
            stats.received += 1
            stats.bytes += len(data)
            if self._writer_idle:
                wake.set()
            # bounded memory: wait for the writer rather than drop anything
            while stats.bytes - stats.written_bytes > limit and queue and self.running:
                time.sleep(0.0005)

        return receive

    # -- writing -------------------------------------------------------------------------------
    def _write_loop(self) -> None:
        queue, writer = self._queue, self.writer
        popleft, write_raw = queue.popleft, writer.write_raw
        timestamp_of = source_timestamp
        stats = self._stats_by_tid
        interval = max(self.options.flush_interval, 0.001)
        idle_wait = min(0.05, interval / 2)
        monotonic = time.monotonic
        last_flush = monotonic()
        dirty = False
        n = 0
        try:
            while True:
                try:
                    tid, data, received, attachment = popleft()
                except IndexError:
                    if not self._running and not queue:
                        break
                    now = monotonic()
                    if dirty and now - last_flush >= interval:
                        writer.flush()
                        last_flush, dirty = now, False
                    self._writer_idle = True
                    if not queue:
                        self._wake.wait(idle_wait)
                    self._wake.clear()
                    self._writer_idle = False
                    continue
                n += 1
                if n % _CLOCK_EVERY == 0 and dirty:  # busy: the disk must not fall behind
                    now = monotonic()
                    if now - last_flush >= interval:
                        writer.flush()
                        last_flush, dirty = now, False
                # the publisher's send time travels in the attachment (either layout)
                sent = timestamp_of(attachment)
                write_raw(tid, data, received, received if sent is None else sent)
                stats[tid].written_bytes += len(data)
                dirty = True
        except Exception as e:  # a full disk, or anything else: recording ends, loudly
            self._fail(e)
            queue.clear()

    def _fail(self, e: BaseException) -> None:
        if self.error is None:
            self.error = e if isinstance(e, BagError) else BagError(str(e) or type(e).__name__)
