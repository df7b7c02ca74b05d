"""Playback: publish a bag's messages again, spaced as they were received.

Messages are published as the CDR bytes stored in the bag (never decoded). A read-ahead thread
fills a bounded queue from the reader; the playing thread sends each message when the
monotonic clock reaches its log time (relative to the first one, divided by the rate). Waiting
is a timed sleep to just short of the deadline and a short spin for the rest, which keeps the
error well under a millisecond without burning a core.

Pause, resume, rate changes and "play next" re-anchor the schedule at the current bag time,
so they never make the player rush to catch up. Publishers use the QoS the bag recorded
(reliable / transient-local only when every recorded publisher offered it).
"""

from __future__ import annotations

import queue
import re
import threading
import time
from collections.abc import Callable, Generator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from ros2lite.bag.errors import BagError
from ros2lite.bag.metadata import TopicMetadata
from ros2lite.bag.qos import playback_qos
from ros2lite.bag.reader import Reader
from ros2lite.qos import QoSProfile
from ros2lite.qos import QoSProfile as Q

if TYPE_CHECKING:
    from ros2lite.node import Node
    from ros2lite.publisher import Publisher
    from ros2lite.type_support import Msg

# what the read-ahead thread hands over: a message (topic, CDR bytes, log and publish time),
# the error that ended reading, or _END
_Ahead = tuple[str, bytes, int, int] | BaseException | None

__all__ = ["SWITCH_INTERVAL", "PlayOptions", "Player"]

_SPIN = 300_000  # ns spent spinning (not sleeping) before each deadline
# The read-ahead thread must not keep the GIL for long while a message is due: with Python's
# default 5 ms switch interval it could make a message that late. The switch interval is the
# process' to set (see ros2lite.util.process.switch_interval), so this is what players ask for.
SWITCH_INTERVAL = 0.0002
_END = None  # what the read-ahead thread puts after the last message


@dataclass
class PlayOptions:
    """How to play; the fields mirror `ros2 bag play`'s options."""

    rate: float = 1.0
    loop: bool = False
    topics: list[str] | None = None
    exclude_topics: list[str] = field(default_factory=list)
    regex: str | None = None
    exclude_regex: str | None = None
    remap: dict[str, str] = field(default_factory=dict)
    start_offset: float = 0.0  # seconds into the bag
    delay: float = 0.0  # seconds before playing (each loop)
    clock_hz: float = 0.0  # publish /clock at this rate (0: no)
    start_paused: bool = False
    read_ahead_queue_size: int = 1000
    qos_overrides: dict[str, QoSProfile] = field(default_factory=dict)
    record_timing: bool = False  # keep each message's lateness (benchmarks)


class Player:
    """Plays `reader` through `node`'s publishers; `play()` blocks until done or `stop()`.

    Control methods (`pause`, `resume`, `toggle_paused`, `play_next`, `set_rate`, `stop`)
    may be called from any thread.
    """

    def __init__(
        self,
        node: Node,
        reader: Reader,
        options: PlayOptions,
        *,
        log: Callable[[str], object] | None = None,
        warn: Callable[[str], object] | None = None,
    ) -> None:
        if options.rate <= 0:
            raise ValueError("rate must be greater than 0")
        self.node = node
        self.reader = reader
        self.options = options
        self._log = log or (lambda _m: None)
        self._warn = warn or self._log
        self._cv = threading.Condition()
        self._paused = options.start_paused
        self._stopped = False
        self._next = 0  # "play next" requests not served yet
        self._rate = options.rate
        self._anchor_bag = 0  # bag time (ns) at _anchor_wall
        self._anchor_wall = 0  # monotonic ns
        self._bag_now = reader.start_time
        self._end = reader.end_time
        self.published = 0
        self.lateness: list[int] = []
        self._publishers: dict[str, Publisher[Msg]] = {}
        self._clock_thread: threading.Thread | None = None
        # where the next burst starts: a log time and how many messages of it were sent
        self._burst_from: tuple[int | None, int] = (None, 0)
        self._prepare()

    # -- set-up --------------------------------------------------------------------------------
    def _selected(self, t: TopicMetadata) -> bool:
        o = self.options
        name = t.name
        if o.topics is not None and name not in o.topics:
            return False
        if name in o.exclude_topics:
            return False
        if o.regex and not re.search(o.regex, name):
            return False
        if o.exclude_regex and re.search(o.exclude_regex, name):
            return False
        return not (o.clock_hz > 0 and name == "/clock")

    def _prepare(self) -> None:
        from ros2lite.interfaces import InterfaceError, get_interface
        from ros2lite.interfaces.parser import validate_type_name
        from ros2lite.interfaces.registry import normalize_name

        for problem in self.reader.shortfalls():
            self._warn(problem)
        if self.options.topics is not None:
            in_bag = {t.name for t in self.reader.topics}
            missing = [
                t
                for t in self.options.topics
                if t.startswith("/") and t not in in_bag and t[1:] not in in_bag
            ]
            if missing and not any(t in in_bag for t in self.options.topics):
                raise BagError(
                    f"None of the topics to play ({', '.join(missing)}) is in the bag; "
                    f"it has: {', '.join(sorted(in_bag)) or 'no topics'}"
                )
            for name in missing:
                self._warn(f"Topic '{name}' is not in the bag; nothing to play for it")

        for t in self.reader.topics:
            if not self._selected(t):
                continue
            if t.serialization_format != "cdr" or not t.type:
                self._warn(
                    f"Topic '{t.name}' is not CDR ({t.serialization_format or '?'}); not playing it"
                )
                continue
            type_name = normalize_name(t.type)
            try:
                validate_type_name(type_name)
            except InterfaceError as e:
                self._warn(f"Topic '{t.name}': {e}; not playing it")
                continue
            msg_type: type[Msg] | str = type_name
            try:
                get_interface(type_name)
                from ros2lite.interfaces import type_hash

                local_hash = type_hash(type_name)
            except (InterfaceError, LookupError, ValueError):
                local_hash = None
            if local_hash is None or (
                t.type_description_hash and t.type_description_hash != local_hash
            ):
                ref = self._bag_type(t, type_name)
                if ref is None:
                    self._warn(
                        f"Topic '{t.name}': type {t.type} is unknown here and the bag "
                        f"holds no definition of it; not playing it"
                    )
                    continue
                msg_type = ref
            qos = self.options.qos_overrides.get(t.name) or playback_qos(
                t.name, t.offered_qos_profiles, self._warn
            )
            target = self.options.remap.get(t.name, t.name)
            self._publishers[t.name] = self.node.create_publisher(msg_type, target, qos)

    def _bag_type(self, t: TopicMetadata, type_name: str) -> type[Msg] | None:
        """A publishable stand-in for a type known only from the bag (hash from the bag, or
        computed from its definition)."""
        from ros2lite.bag.definitions import type_ref

        digest = t.type_description_hash
        if not digest:
            from ros2lite.interfaces.hashing import type_hash

            types = self.reader.bag_types()
            if type_name not in types.known:
                return None
            try:
                digest = type_hash(type_name, types)
            except (ValueError, LookupError):
                return None
        return type_ref(type_name, digest)

    @property
    def topics(self) -> list[str]:
        """The bag topics being played, sorted."""
        return sorted(self._publishers)

    # -- control -------------------------------------------------------------------------------
    @property
    def paused(self) -> bool:
        """Whether playback is paused."""
        return self._paused

    @property
    def rate(self) -> float:
        """The playback rate (1.0: real time)."""
        return self._rate

    def _reanchor(self) -> None:
        # caller holds the lock: the schedule continues from the current bag time
        self._anchor_bag = self._bag_now
        self._anchor_wall = time.monotonic_ns()

    def pause(self) -> None:
        """Hold playback (any thread)."""
        with self._cv:
            if not self._paused:
                self._bag_now = self.bag_time()
                self._paused = True
                self._cv.notify_all()
                self._log("Pausing play.")

    def resume(self) -> None:
        """Go on playing from where it was paused (any thread)."""
        with self._cv:
            if self._paused:
                self._paused = False
                self._reanchor()
                self._cv.notify_all()
                self._log("Resuming play.")

    def toggle_paused(self) -> None:
        """Pause or resume, as the space key does."""
        if self._paused:
            self.resume()
        else:
            self.pause()

    def play_next(self) -> None:
        """While paused, publish the next message at once."""
        with self._cv:
            if self._paused:
                self._next += 1
                self._cv.notify_all()

    def set_rate(self, rate: float) -> bool:
        """Change the playback rate from now on (False if not positive)."""
        if rate <= 0:
            return False
        with self._cv:
            self._bag_now = self.bag_time()
            self._rate = rate
            self._reanchor()
            self._cv.notify_all()
        self._log(f"Set rate to {rate:g}")
        return True

    def stop(self) -> None:
        """End playback; play() returns."""
        with self._cv:
            self._stopped = True
            self._cv.notify_all()

    @property
    def stopped(self) -> bool:
        """Whether stop() was called."""
        return self._stopped

    def bag_time(self) -> int:
        """The bag time being played now (ns), frozen while paused."""
        if self._paused or self._anchor_wall == 0:
            return self._bag_now
        elapsed = time.monotonic_ns() - self._anchor_wall
        # the bag's clock stops at its last message (until a loop starts it over)
        return min(self._anchor_bag + int(max(elapsed, 0) * self._rate), self._end)

    # -- playing -------------------------------------------------------------------------------
    def play(self) -> None:
        """Play (and loop, if asked) until the end or `stop()`."""
        if self.options.clock_hz > 0:
            self._clock_thread = threading.Thread(
                target=self._clock_loop, daemon=True, name="ros2lite-bag-clock"
            )
            self._clock_thread.start()
        try:
            while not self._stopped:
                self._play_once()
                if not self.options.loop:
                    break
        finally:
            with self._cv:
                self._stopped = True
                self._cv.notify_all()
            if self._clock_thread is not None:
                self._clock_thread.join(timeout=1)

    def run(self, stop: threading.Event, on_tick: Callable[[], object] | None = None) -> None:
        """Play on a thread of its own until the end, `stop` is set (a signal) or it fails
        (the failure is raised here); `on_tick()` about ten times a second meanwhile."""
        errors: list[BaseException] = []

        def play() -> None:
            try:
                self.play()
            except BaseException as e:
                errors.append(e)

        thread = threading.Thread(target=play, daemon=True, name="ros2lite-bag-player")
        thread.start()
        try:
            while thread.is_alive() and not stop.is_set():
                thread.join(0.1)
                if on_tick is not None:
                    on_tick()
        finally:
            self.stop()
            thread.join(timeout=2)
        if errors:
            raise errors[0]

    def _in_range(self, start: int) -> Generator[tuple[str, bytes, int, int]]:
        """The selected topics' messages from `start` on, without those whose log time lies
        outside the bag's own range (a corrupt time, the year 2500 say, would have playback
        wait for it): they are counted and reported once at the end."""
        first, last = self.reader.start_time, self.reader.end_time
        refused = 0
        try:
            for item in self.reader.raw_messages(self._publishers, start=start):
                if first <= item[2] <= last:
                    yield item
                else:
                    refused += 1
        finally:
            if refused:
                self._warn(
                    f"{refused} message(s) have log times outside the bag's own range "
                    f"[{first}, {last}] ns (corrupt); not playing them"
                )

    def _reader_thread(self, out: queue.Queue[_Ahead], start: int) -> None:
        put = out.put
        messages = self._in_range(start)
        try:
            for item in messages:
                while not self._stopped:
                    try:
                        put(item, timeout=0.1)
                        break
                    except queue.Full:
                        continue
                if self._stopped:
                    return
        except Exception as e:
            put(e)
            return
        finally:
            messages.close()
        put(_END)

    def burst(self, num_messages: int = 0) -> int:
        """Publish the next `num_messages` messages (0: all the rest) as fast as possible,
        ignoring their timing, as `ros2 bag burst` does; returns how many were published.
        Starts at the start offset, or where an earlier burst stopped; `stop()` ends it."""
        if num_messages < 0:
            raise ValueError("num_messages must not be negative")
        start, skip = self._burst_from
        if start is None:
            start = self.reader.start_time + int(self.options.start_offset * 1e9)
        publishers = self._publishers
        sent = 0
        same_time = 0  # messages published at the last log time (a resumed burst skips them)
        last_time = -1
        messages = self._in_range(start)
        try:
            for topic, data, log_time, _ in messages:
                if skip and log_time == start:
                    skip -= 1
                    continue
                if self._stopped or (num_messages and sent >= num_messages):
                    self._burst_from = (log_time, same_time if log_time == last_time else 0)
                    return sent
                publishers[topic].publish(data)
                sent += 1
                self.published += 1
                self._bag_now = log_time
                same_time = same_time + 1 if log_time == last_time else 1
                last_time = log_time
            self._burst_from = (self._end + 1, 0)
        finally:
            messages.close()
        return sent

    def _play_once(self) -> None:
        start = self.reader.start_time + int(self.options.start_offset * 1e9)
        ahead: queue.Queue[_Ahead] = queue.Queue(max(self.options.read_ahead_queue_size, 1))
        feeder = threading.Thread(
            target=self._reader_thread,
            args=(ahead, start),
            daemon=True,
            name="ros2lite-bag-read-ahead",
        )
        feeder.start()
        with self._cv:
            self._bag_now = start
            self._reanchor()
            self._anchor_wall += int(self.options.delay * 1e9)
        publishers = self._publishers
        cv = self._cv
        monotonic = time.monotonic_ns
        lateness = self.lateness if self.options.record_timing else None
        try:
            while not self._stopped:
                try:
                    item = ahead.get(timeout=0.1)
                except queue.Empty:
                    continue  # starved (or stopping: the reader then puts nothing more)
                if item is _END:
                    return
                if isinstance(item, BaseException):
                    raise item
                topic, data, log_time, _ = item
                forced = False
                target = 0
                with cv:
                    while not self._stopped:
                        if self._paused:
                            if self._next:
                                self._next -= 1
                                forced = True
                                self._bag_now = log_time
                                break
                            cv.wait()
                            continue
                        target = self._anchor_wall + int((log_time - self._anchor_bag) / self._rate)
                        wait = target - monotonic()
                        if wait <= _SPIN:
                            break
                        cv.wait((wait - _SPIN) / 1e9)
                    else:
                        return
                if not forced:
                    while monotonic() < target:
                        pass
                publishers[topic].publish(data)
                if lateness is not None and not forced:
                    lateness.append(monotonic() - target)
                if not self._paused:
                    self._bag_now = log_time
                self.published += 1
        finally:
            if self._stopped:
                feeder.join(timeout=0.5)  # it notices the stop within 0.1 s

    def _clock_loop(self) -> None:
        from ros2lite.interfaces import get_interface

        clock_type = get_interface("rosgraph_msgs/msg/Clock")
        time_type = get_interface("builtin_interfaces/msg/Time")

        pub = self.node.create_publisher(clock_type, "/clock", Q(depth=1))
        period = 1.0 / self.options.clock_hz
        next_tick = time.monotonic()
        while not self._stopped:
            sec, nsec = divmod(self.bag_time(), 1_000_000_000)
            pub.publish(clock_type(clock=time_type(sec=sec, nanosec=nsec)))
            next_tick += period
            with self._cv:
                self._cv.wait(max(next_tick - time.monotonic(), 0))
