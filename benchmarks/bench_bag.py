"""Bag benchmarks: recording throughput with zero loss, playback timing, `bag info` on 1 GiB.

Each benchmark starts its own router on a free loopback port with a private domain.

* record: a publisher *process* sends N samples back to back (KEEP_ALL + RELIABLE, so Zenoh
  blocks instead of dropping) while the library's `Recorder` (what `bag record` runs) records
  them in this process into a temp dir. Rate = N / (first arrival → last message handed to
  the OS by the writer thread); the run fails unless the bag holds all N, in order. Baseline:
  the raw `mcap` Writer writing the same N payloads (same sizes, chunking, no compression)
  into a file in this process; ratio = record rate / raw writer rate. The publisher's own
  send rate is printed with BENCH_BAG_VERBOSE=1 (when it is lower than the record rate the
  publisher, not the recorder, set the pace). Small: `std_msgs/String` 'Hello World: i'
  (~30 B). Large: 1 MiB strings, reported in MB/s (10^6 B).
* record, the two halves measured separately (same payloads, medians of RUNS):
  - writer path (`bag_record_writer_*`): the Recorder's real writer loop draining a queue
    that already holds the N received samples into a bag, against the raw mcap writer
    (ratio; this is the part that must keep up with the raw writer).
  - receive path (`bag_record_receive_*`): the recorder's subscription (a
    MonitoredSubscription handing bytes, attachment and arrival time to the recorder's
    queue) receiving the publisher's N samples with nothing written, against a raw zenoh
    subscriber doing the same (payload and attachment copied out, stamped, queued).
  The end-to-end ratio is also given against the floor those raw parts set together in one
  process (`bag_record_*_vs_raw_floor`: 1 / (1/raw writer + 1/raw receive)), since Python
  runs the receiving and the writing thread one at a time.
* play: a 1 kHz bag of 3000 small messages played by the library's `Player`; lateness =
  actual publish time - scheduled time of every message; p50 and p99 reported in ms, ratio
  = value / the 1 ms target.
* info: a 1 GiB bag (1024 x 1 MiB) written to a temp dir and deleted afterwards; the wall
  time of the real `python -m ros2lite bag info` process (median of 5), once with
  metadata.yaml and once without it (the MCAP summary path). Ratio = time / the 200 ms
  target; the bare interpreter start-up (`python -c pass`) is printed as `python_startup`.

* huge message: one legitimate 256 MiB message in a zstd chunk (with a summary) read whole by
  the library's Reader (what `bag play` does before it publishes), against the floor of
  inflating the same chunk once with zstd in this process (R5-B4: its record grew by
  `bytes +=`, 33 s). Ratio = read time / floor.

Medians of RUNS runs are reported; single runs on a small shared VM scatter widely.
"""

from __future__ import annotations

import contextlib
import os
import random
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from common import report, wall

RUNS = int(os.environ.get("BENCH_RUNS", 3))  # interleaved runs (median)
VERBOSE = bool(os.environ.get("BENCH_BAG_VERBOSE"))

PUBLISHER = r"""
import sys, time
from ros2lite.context import Context
from ros2lite.node import Node
from ros2lite.interfaces import get_interface, serialize
from ros2lite.qos import HistoryPolicy, QoSProfile
topic, n, size = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
String = get_interface('std_msgs/msg/String')
if size:
    big = serialize(String(data='x' * size))
    payloads = [big] * n
else:
    payloads = [serialize(String(data=f'Hello World: {i}')) for i in range(n)]
ctx = Context(); ctx.init([])
node = Node('bench_bag_publisher', context=ctx, enable_rosout=False)
pub = node.create_publisher(String, topic, QoSProfile(history=HistoryPolicy.KEEP_ALL))
while pub.get_subscription_count() < 1:
    time.sleep(0.02)
time.sleep(0.5)
publish = pub.publish
t0 = time.perf_counter()
for p in payloads:
    publish(p)
dt = time.perf_counter() - t0
print(n / dt, flush=True)
time.sleep(1.0)
ctx.shutdown()
"""


def _free_port() -> int:
    import socket

    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return int(sock.getsockname()[1])


@contextlib.contextmanager
def private_router() -> Iterator[dict[str, str]]:
    """A router on a free port, and this process (and children) pointed at it."""
    import zenoh

    from ros2lite.transport.config import router_config

    endpoint = f"tcp/127.0.0.1:{_free_port()}"
    saved = dict(os.environ)
    for key in ("ZENOH_CONFIG_OVERRIDE", "ZENOH_SESSION_CONFIG_URI", "ZENOH_ROUTER_CONFIG_URI"):
        os.environ.pop(key, None)
    router = zenoh.open(router_config(endpoint, env={}))
    os.environ.update(ROS2LITE_ROUTER=endpoint, ROS_DOMAIN_ID=str(random.randint(100, 232)))
    try:
        yield dict(os.environ)
    finally:
        router.close()
        os.environ.clear()
        os.environ.update(saved)


def raw_mcap_rate(payloads: list[bytes], directory: str) -> float:
    """Messages per second of the bare mcap Writer writing these payloads to a file."""
    from mcap.writer import CompressionType, IndexType, Writer

    from ros2lite.bag.storage.mcap import DEFAULT_CHUNK_SIZE
    from ros2lite.interfaces import definition_text

    path = os.path.join(directory, f"raw_{time.monotonic_ns()}.mcap")
    with open(path, "wb") as f:
        t0 = time.perf_counter()
        w = Writer(
            f,
            chunk_size=DEFAULT_CHUNK_SIZE,
            compression=CompressionType.NONE,
            index_types=IndexType.ALL,
        )
        w.start(profile="ros2", library="bench")
        sid = w.register_schema(
            "std_msgs/msg/String", "ros2msg", definition_text("std_msgs/msg/String").encode()
        )
        cid = w.register_channel("/bench", "cdr", sid, {})
        add = w.add_message
        stamp = time.time_ns()
        for i, p in enumerate(payloads):
            add(cid, stamp + i, p, stamp + i)
        w.finish()
        dt = time.perf_counter() - t0
    os.unlink(path)
    return len(payloads) / dt


def record_once(n: int, size: int, directory: str) -> tuple[float, float]:
    """(recorded msg/s, publisher msg/s) of one lossless recording run."""
    from ros2lite.bag import Reader, Writer
    from ros2lite.bag.recorder import Recorder, RecordOptions
    from ros2lite.context import Context
    from ros2lite.node import Node

    topic = f"/bench_bag_{time.monotonic_ns()}"
    bag = os.path.join(directory, f"bag_{time.monotonic_ns()}")
    ctx = Context()
    ctx.init([])
    try:
        node = Node("bench_bag_recorder", context=ctx, enable_rosout=False)
        writer = Writer(bag)
        recorder = Recorder(node, writer, RecordOptions(topics=[topic], polling_interval=0.02))
        recorder.start()
        publisher = subprocess.Popen(
            [sys.executable, "-c", PUBLISHER, topic, str(n), str(size)],
            stdout=subprocess.PIPE,
            text=True,
        )
        while writer.message_count < n and publisher.poll() is None:
            time.sleep(0.001)
        while writer.message_count < n:  # the publisher is gone; the queue drains
            time.sleep(0.001)
        done_ns = time.time_ns()
        out, _ = publisher.communicate(timeout=60)
        recorder.stop()
        if recorder.error is not None:
            raise RuntimeError(f"recording failed: {recorder.error}")
        with Reader(bag) as reader:
            if reader.message_count != n:
                raise RuntimeError(f"lost messages: {reader.message_count} of {n}")
            first = next(t for _, _, t in reader.messages(raw=True))
        shutil.rmtree(bag)
        return n / ((done_ns - first) / 1e9), float(out.strip() or 0)
    finally:
        ctx.try_shutdown()


def writer_path_rate(payloads: list[bytes], directory: str) -> float:
    """Messages per second of the Recorder's writer loop over a queue of received samples."""
    from ros2lite.bag import Writer
    from ros2lite.bag.recorder import Recorder, RecordOptions, TopicStats
    from ros2lite.context import Context
    from ros2lite.node import Node
    from ros2lite.transport.attachment import pack_attachment

    ctx = Context()
    ctx.init([])
    try:
        node = Node("bench_bag_writer", context=ctx, enable_rosout=False)
        writer = Writer(os.path.join(directory, f"writer_{time.monotonic_ns()}"))
        recorder = Recorder(node, writer, RecordOptions(topics=["/bench"]))
        writer.open()
        tid = writer.create_topic("/bench", "std_msgs/msg/String")
        recorder._stats_by_tid[tid] = TopicStats("/bench", "std_msgs/msg/String")
        stamp, gid = time.time_ns(), bytes(16)
        recorder._queue.extend(
            (tid, p, stamp + i, pack_attachment(i + 1, stamp + i, gid))
            for i, p in enumerate(payloads)
        )
        t0 = time.perf_counter()
        recorder._write_loop()  # (white box) the loop of the writer thread; ends when drained
        writer.close()
        dt = time.perf_counter() - t0
        if recorder.error is not None or writer.message_count != len(payloads):
            raise RuntimeError(f"writer path failed: {recorder.error}")
        shutil.rmtree(writer.path)
        return len(payloads) / dt
    finally:
        ctx.try_shutdown()


def receive_rate(n: int, size: int, raw: bool) -> float:
    """Messages per second received from a publisher process by the recorder's subscription
    (raw=False) or by a raw zenoh subscriber doing the same work (raw=True); nothing written."""
    import zenoh

    from ros2lite.context import Context
    from ros2lite.interfaces import type_hash
    from ros2lite.monitor.subscription import MonitoredSubscription
    from ros2lite.node import Node
    from ros2lite.qos import HistoryPolicy, QoSProfile
    from ros2lite.transport.keys import EntityKind, endpoint_token, topic_key

    topic = f"/bench_bag_rx_{time.monotonic_ns()}"
    ctx = Context()
    ctx.init([])
    stamps: list[int] = []
    queue: list[tuple[bytes, bytes, int]] = []
    done = threading.Event()

    def on_payload(data: bytes, attachment: bytes, received: int) -> None:
        queue.append((data, attachment, received))
        if len(queue) == n:
            stamps.append(time.perf_counter_ns())
            done.set()
        elif len(queue) == 1:
            stamps.append(time.perf_counter_ns())

    try:
        node = Node("bench_bag_rx", context=ctx, enable_rosout=False)
        qos = QoSProfile(history=HistoryPolicy.KEEP_ALL)
        if raw:
            from ros2lite.transport.session import as_zenoh, declare_token

            session = as_zenoh(ctx.require())
            key = topic_key(
                ctx.domain_id, topic, "std_msgs/msg/String", type_hash("std_msgs/msg/String")
            )
            sub = session.declare_subscriber(key, zenoh.handlers.FifoChannel(4096))
            # only the token of a subscription, so the publisher (which waits for one) goes
            token = declare_token(
                session,
                endpoint_token(
                    ctx.domain_id,
                    ctx.zid,
                    node.node_id,
                    ctx.next_entity_id(),
                    EntityKind.SUBSCRIPTION,
                    node.get_namespace(),
                    node.get_name(),
                    topic,
                    "std_msgs/msg/String",
                    type_hash("std_msgs/msg/String"),
                    qos,
                ),
            )

            def drain() -> None:
                now = time.time_ns
                with contextlib.suppress(zenoh.ZError):
                    for sample in sub.handler:
                        att = sample.attachment
                        if att is not None:
                            on_payload(sample.payload.to_bytes(), att.to_bytes(), now())

            threading.Thread(target=drain, daemon=True).start()
        else:
            MonitoredSubscription(
                node, "std_msgs/msg/String", topic, None, qos, on_payload=on_payload
            )
        publisher = subprocess.Popen(
            [sys.executable, "-c", PUBLISHER, topic, str(n), str(size)],
            stdout=subprocess.PIPE,
            text=True,
        )
        publisher_ok = done.wait(120)
        publisher.communicate(timeout=60)
        if not publisher_ok:
            raise RuntimeError(f"lost messages: {len(queue)} of {n} arrived")
        if raw:
            sub.undeclare()
            token.undeclare()
        return (n - 1) / ((stamps[1] - stamps[0]) / 1e9)
    finally:
        ctx.try_shutdown()


def bench_record(name: str, n: int, size: int) -> None:
    from ros2lite.interfaces import get_interface, serialize

    String = get_interface("std_msgs/msg/String")
    if size:
        payloads = [serialize(String(data="x" * size))] * n
    else:
        payloads = [serialize(String(data=f"Hello World: {i}")) for i in range(n)]
    nbytes = sum(len(p) for p in payloads) / n
    rates: dict[str, list[float]] = {k: [] for k in ("rec", "raw", "wpath", "rx", "rawrx")}
    with private_router(), tempfile.TemporaryDirectory(dir=os.environ.get("BENCH_TMP")) as tmp:
        from ros2lite.runtime.memory import keep_large_buffers

        keep_large_buffers()  # what the recorder's node does: the raw parts get it too
        for _ in range(RUNS):  # interleaved, so drifting load hits every part alike
            rate, sent = record_once(n, size, tmp)
            rates["rec"].append(rate)
            rates["raw"].append(raw_mcap_rate(payloads, tmp))
            rates["wpath"].append(writer_path_rate(payloads, tmp))
            rates["rx"].append(receive_rate(n, size, raw=False))
            rates["rawrx"].append(receive_rate(n, size, raw=True))
            if VERBOSE:
                last = {k: round(v[-1]) for k, v in rates.items()}
                print(f"  {name}: {last} (publisher sent {sent:.0f} msg/s)", file=sys.stderr)
    med = {k: statistics.median(v) for k, v in rates.items()}
    floor = 1 / (1 / med["raw"] + 1 / med["rawrx"])
    scale, unit = (nbytes / 1e6, "MB/s") if size else (1.0, "msg/s")
    report(name, med["rec"] * scale, unit, med["rec"] / med["raw"])
    report(f"{name}_vs_raw_floor", med["rec"] * scale, unit, med["rec"] / floor)
    short = name.removeprefix("bag_record_")
    report(f"bag_record_writer_{short}", med["wpath"] * scale, unit, med["wpath"] / med["raw"])
    report(f"bag_record_receive_{short}", med["rx"] * scale, unit, med["rx"] / med["rawrx"])


def bench_record_small() -> None:
    bench_record("bag_record_string", 200_000, 0)


def bench_record_1mib() -> None:
    bench_record("bag_record_1mib", 400, 1024 * 1024)


def bench_play() -> None:
    from ros2lite.bag import Reader, Writer
    from ros2lite.bag.player import Player, PlayOptions
    from ros2lite.context import Context
    from ros2lite.interfaces import get_interface
    from ros2lite.node import Node

    String = get_interface("std_msgs/msg/String")
    p50s, p99s = [], []
    with private_router(), tempfile.TemporaryDirectory() as tmp:
        bag = os.path.join(tmp, "kilohertz")
        with Writer(bag) as w:
            for i in range(3000):
                w.write(
                    "/bench_play",
                    String(data=f"tick {i}"),
                    1_700_000_000_000_000_000 + i * 1_000_000,
                )
        for _ in range(RUNS):
            ctx = Context()
            ctx.init([])
            try:
                node = Node("bench_bag_player", context=ctx, enable_rosout=False)
                with Reader(bag) as reader:
                    player = Player(node, reader, PlayOptions(record_timing=True))
                    player.play()
                late = sorted(player.lateness)
            finally:
                ctx.try_shutdown()
            p50s.append(late[len(late) // 2] / 1e6)
            p99s.append(late[int(len(late) * 0.99)] / 1e6)
            if VERBOSE:
                print(
                    f"  play: p50 {p50s[-1]:.3f} ms, p99 {p99s[-1]:.3f} ms, "
                    f"max {late[-1] / 1e6:.3f} ms",
                    file=sys.stderr,
                )
    p50, p99 = statistics.median(p50s), statistics.median(p99s)
    report("bag_play_1khz_p50", p50, "ms", p50 / 1.0)
    report("bag_play_1khz_p99", p99, "ms", p99 / 1.0)


def bench_info() -> None:
    from ros2lite.bag import Writer
    from ros2lite.interfaces import get_interface, serialize

    String = get_interface("std_msgs/msg/String")
    payload = serialize(String(data="x" * (1024 * 1024 - 16)))
    with tempfile.TemporaryDirectory(dir=os.environ.get("BENCH_TMP")) as tmp:
        bag = Path(tmp) / "gib"
        with Writer(bag) as w:
            tid = w.create_topic("/big", "std_msgs/msg/String")
            t = time.time_ns()
            for i in range(1024):
                w.write_raw(tid, payload, t + i * 10_000_000, t)
        size = sum(p.stat().st_size for p in bag.iterdir())
        if size < 2**30:
            raise RuntimeError(f"bag is only {size} bytes")
        cmd = [sys.executable, "-m", "ros2lite", "bag", "info", str(bag)]
        startup = wall([sys.executable, "-c", "pass"], runs=5)
        with_yaml = wall(cmd, runs=5)
        (bag / "metadata.yaml").unlink()
        summary_only = wall(cmd, runs=5)
    if VERBOSE:
        print(f"  python_startup {startup * 1e3:.1f} ms", file=sys.stderr)
    report("bag_info_1gib", with_yaml * 1e3, "ms", with_yaml / 0.2)
    report("bag_info_1gib_mcap_summary", summary_only * 1e3, "ms", summary_only / 0.2)


def bench_huge_message() -> None:
    import struct

    import zstandard
    from mcap.writer import CompressionType
    from mcap.writer import Writer as McapWriter

    from ros2lite.bag import Reader

    size = 256 << 20
    data = b"\0\1\0\0" + struct.pack("<I", size) + b"a" * (size - 1) + b"\0"
    reads, floors = [], []
    with tempfile.TemporaryDirectory(dir=os.environ.get("BENCH_TMP")) as tmp:
        bag = Path(tmp) / "huge"
        bag.mkdir()
        with open(bag / "huge_0.mcap", "wb") as f:
            writer = McapWriter(f, compression=CompressionType.ZSTD)
            writer.start(profile="ros2", library="bench")
            sid = writer.register_schema("std_msgs/msg/String", "ros2msg", b"string data")
            cid = writer.register_channel("/huge", "cdr", sid)
            writer.add_message(cid, log_time=1, publish_time=1, data=data)
            writer.finish()
        packed = zstandard.ZstdCompressor().compress(data)
        for _ in range(RUNS):
            start = time.perf_counter()
            zstandard.ZstdDecompressor().decompress(packed, max_output_size=len(data))
            floors.append(time.perf_counter() - start)
            start = time.perf_counter()
            with Reader(bag) as reader:
                [(_, got, _, _)] = list(reader.raw_messages())
            reads.append(time.perf_counter() - start)
            assert len(got) == len(data)
            del got
    read, floor = statistics.median(reads), statistics.median(floors)
    report("bag_read_256mib_message", read, "s", read / floor)


BENCHES: dict[str, Any] = {
    "bag_record_string": bench_record_small,
    "bag_record_1mib": bench_record_1mib,
    "bag_play": bench_play,
    "bag_info": bench_info,
    "bag_huge_message": bench_huge_message,
}
