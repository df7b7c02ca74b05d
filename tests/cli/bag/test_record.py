"""`bag record` as a real process against a real router: every published message is in the
bag after SIGINT or SIGTERM, a SIGKILLed recording is recovered by reindex, junk on a topic
is recorded as it came, and failures are one clear line."""

from __future__ import annotations

import os
import resource
import signal
import time
from pathlib import Path
from typing import Any

from ros2lite.bag import Reader
from ros2lite.bag.metadata import read_metadata_file
from ros2lite.interfaces import get_interface, serialize
from ros2lite.qos import DurabilityPolicy, HistoryPolicy, QoSProfile

from ..conftest import run_process
from .conftest import node_up, on_disk, play, subscribed, wait_until

String = get_interface("std_msgs/msg/String")
KEEP_ALL = QoSProfile(history=HistoryPolicy.KEEP_ALL)


def publish_all(pub: Any, count: int, prefix: str = "msg") -> list[str]:
    sent = [f"{prefix} {i}" for i in range(count)]
    for text in sent:
        pub.publish(String(data=text))
    return sent


def test_record_then_play_round_trip(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, listener: Any, topic: str
) -> None:
    pub = node.create_publisher(String, topic, KEEP_ALL)
    rec = recording(tmp_path / "bag", "--topics", topic)
    wait_until(lambda: subscribed(ros_context, topic), timeout=20)
    sent = publish_all(pub, 2000)
    wait_until(lambda: on_disk(tmp_path / "bag") == 2000, timeout=20)
    code, _out, err = rec.finish(signal.SIGINT)
    assert code == 0, err
    assert f"Subscribed to topic '{topic}'" in err and "Recording stopped" in err
    with Reader(tmp_path / "bag") as bag:
        got = [(t, m.data, stamp) for t, m, stamp in bag]
        raw = list(bag.raw_messages())
    assert [g[1] for g in got] == sent  # nothing lost, in order
    assert {g[0] for g in got} == {topic}
    assert all(p <= t for _, _, t, p in raw)  # sent before received
    assert raw[0][3] != raw[0][2]  # publish time = sender's stamp
    meta = read_metadata_file(tmp_path / "bag" / "metadata.yaml")
    assert meta.message_count == 2000
    qos = meta.topic(topic).topic_metadata.offered_qos_profiles  # type: ignore[union-attr]
    assert qos[0].history == HistoryPolicy.KEEP_ALL
    # …and back out through `bag play` to a subscriber
    lst = listener(topic, String, KEEP_ALL)
    wait_until(lambda: subscribed(ros_context, topic), timeout=10)
    result = play(str(tmp_path / "bag"), "-r", "20")
    assert result.returncode == 0, result.stderr
    wait_until(lambda: len(lst.messages) == 2000, timeout=10)
    assert [m.data for m in lst.messages] == sent


def test_sigterm_finishes_the_bag_and_late_topics_are_picked_up(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, topic: str
) -> None:
    rec = recording(
        tmp_path / "bag",
        "-e",
        f"^{topic}",
        "-x",
        "skip$",
        "--exclude-topics",
        f"{topic}/excluded",
        "-p",
        "50",
    )
    wait_until(lambda: node_up(ros_context), timeout=20)  # up before any of these topics
    pubs = {
        name: node.create_publisher(String, name, KEEP_ALL)
        for name in (f"{topic}/late", f"{topic}/skip", f"{topic}/excluded", f"{topic}/_hidden")
    }
    wait_until(lambda: subscribed(ros_context, f"{topic}/late"), timeout=20)
    for name, pub in pubs.items():
        publish_all(pub, 10, name)
    wait_until(lambda: on_disk(tmp_path / "bag", f"{topic}/late") == 10, timeout=20)
    code, _out, err = rec.finish(signal.SIGTERM)
    assert code == 0, err
    with Reader(tmp_path / "bag") as bag:
        assert [t.name for t in bag.topics] == [f"{topic}/late"]
        assert bag.message_count == 10


def test_latched_messages_are_recorded(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, topic: str
) -> None:
    latched = QoSProfile(durability=DurabilityPolicy.TRANSIENT_LOCAL, depth=3)
    pub = node.create_publisher(String, topic, latched)
    publish_all(pub, 3, "latched")  # before any recorder exists
    rec = recording(tmp_path / "bag", "--topics", topic)
    wait_until(lambda: on_disk(tmp_path / "bag") == 3, timeout=20)
    code, _out, err = rec.finish()
    assert code == 0, err
    with Reader(tmp_path / "bag") as bag:
        assert [m.data for _, m, _ in bag] == ["latched 0", "latched 1", "latched 2"]
        profile = bag.topic(topic).offered_qos_profiles[0]  # type: ignore[union-attr]
        assert profile.durability == DurabilityPolicy.TRANSIENT_LOCAL


def test_sigkill_then_reindex_recovers(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, topic: str
) -> None:
    pub = node.create_publisher(String, topic, KEEP_ALL)
    rec = recording(tmp_path / "bag", "--topics", topic)
    wait_until(lambda: subscribed(ros_context, topic), timeout=20)
    sent = publish_all(pub, 500)
    wait_until(lambda: on_disk(tmp_path / "bag") == 500, timeout=20)  # all in finished chunks
    rec.finish(signal.SIGKILL)
    assert not (tmp_path / "bag" / "metadata.yaml").exists()
    result = run_process("bag", "reindex", str(tmp_path / "bag"))
    # one line says what the killed recording left
    assert result.code == 0 and len(result.err.splitlines()) == 1, result.err
    assert result.err.startswith(f"[WARN] [ros2bag]: '{tmp_path / 'bag' / 'bag_0.mcap'}' is ")
    assert result.err.endswith(": 500 messages recovered\n"), result.err
    from rosbags.highlevel import AnyReader

    with AnyReader([tmp_path / "bag"]) as oracle:
        conns = [c.topic for c in oracle.connections]
        got = [oracle.deserialize(raw, c.msgtype).data for c, _, raw in oracle.messages()]
    assert got == sent and conns == [topic]


def test_random_bytes_are_recorded_as_they_came(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, topic: str
) -> None:
    pub = node.create_publisher(String, topic, KEEP_ALL)
    rec = recording(tmp_path / "bag", "--topics", topic)
    wait_until(lambda: subscribed(ros_context, topic), timeout=20)
    junk = [os.urandom(n) for n in (0, 1, 3, 17, 4096, 100_000)]
    good = serialize(String(data="still fine"))
    for blob in junk:
        pub.publish(blob)
    pub.publish(good)
    wait_until(lambda: on_disk(tmp_path / "bag") == len(junk) + 1, timeout=20)
    assert rec.proc.poll() is None  # still recording
    code, _out, err = rec.finish()
    assert code == 0, err
    with Reader(tmp_path / "bag") as bag:
        raw = [data for _, data, _ in bag.messages(raw=True)]
        decoded = [m for _, m, _ in bag]
    assert raw == [*junk, good]
    assert decoded[-1].data == "still fine" and decoded[4] == junk[4]


def test_split_and_compressed_recording(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, topic: str
) -> None:
    pub = node.create_publisher(String, topic, KEEP_ALL)
    rec = recording(
        tmp_path / "bag",
        "--topics",
        topic,
        "--max-bag-size",
        "300000",
        "--compression-format",
        "zstd",
    )
    wait_until(lambda: subscribed(ros_context, topic), timeout=20)
    for i in range(300):
        pub.publish(String(data=f"{i:05d}" + os.urandom(1500).hex()))
    wait_until(lambda: on_disk(tmp_path / "bag") == 300, timeout=20)
    code, _out, err = rec.finish()
    assert code == 0, err
    meta = read_metadata_file(tmp_path / "bag" / "metadata.yaml")
    assert len(meta.files) >= 2 and meta.message_count == 300
    from mcap.reader import make_reader

    with open(tmp_path / "bag" / meta.files[0].path, "rb") as f:
        summary = make_reader(f).get_summary()
        assert summary is not None
        assert {c.compression for c in summary.chunk_indexes} == {"zstd"}
    with Reader(tmp_path / "bag") as bag:
        assert [m.data[:5] for _, m, _ in bag] == [f"{i:05d}" for i in range(300)]


def _small_file_limit() -> None:
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # writes past the limit fail: EFBIG
    resource.setrlimit(resource.RLIMIT_FSIZE, (200_000, 200_000))


def test_full_disk_is_one_error_and_keeps_what_was_written(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, topic: str
) -> None:
    pub = node.create_publisher(String, topic, KEEP_ALL)
    rec = recording(tmp_path / "bag", "--topics", topic, preexec=_small_file_limit)
    wait_until(lambda: subscribed(ros_context, topic), timeout=20)
    publish_all(pub, 20, "early")
    wait_until(lambda: on_disk(tmp_path / "bag") == 20, timeout=20)
    for i in range(100):
        pub.publish(String(data=f"big {i} " + "x" * 10_000))
    rec.proc.wait(timeout=30)  # the recorder ends by itself: no signal is sent
    code, _out, err = rec.finish()
    assert code == 1
    lines = [line for line in err.splitlines() if line.startswith("[ERROR]")]
    assert len(lines) == 1 and "File too large" in lines[0], err
    assert "Traceback" not in err
    with Reader(tmp_path / "bag") as bag:
        got = [m.data for _, m, _ in bag]
        assert bag.message_count == len(got)  # metadata.yaml says what the file holds
    assert got[:20] == [f"early {i}" for i in range(20)]


def test_bad_options_and_paths(tmp_path: Path, ros_router: str) -> None:
    none = run_process("bag", "record", "-o", str(tmp_path / "x"))
    assert none.code == 1 and none.err.startswith("[ERROR] [ros2bag]: Need to specify")
    (tmp_path / "exists").mkdir()
    exists = run_process("bag", "record", "-a", "-o", str(tmp_path / "exists"))
    assert (exists.code, exists.err) == (
        1,
        f"[ERROR] [ros2bag]: Output folder '{tmp_path / 'exists'}' already exists.\n",
    )
    (tmp_path / "file").write_text("")
    under_file = run_process("bag", "record", "-a", "-o", str(tmp_path / "file" / "bag"))
    assert under_file.code == 1 and len(under_file.err.splitlines()) == 1
    assert "Cannot create" in under_file.err
    regex = run_process("bag", "record", "-e", "(", "-o", str(tmp_path / "r"))
    assert regex.code == 1 and "Invalid regular expression" in regex.err
    assert not (tmp_path / "r").exists() and not (tmp_path / "x").exists()


def test_start_paused_and_no_discovery_record_nothing(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, topic: str
) -> None:
    early = node.create_publisher(String, topic, KEEP_ALL)
    paused = recording(tmp_path / "paused", "--topics", topic, "--start-paused")
    blind = recording(tmp_path / "blind", "-e", f"^{topic}/late", "--no-discovery")
    wait_until(lambda: subscribed(ros_context, topic), timeout=20)
    wait_until(lambda: node_up(ros_context), timeout=20)
    # the rest shows that nothing comes, so only a bounded wait can: the blind recorder's one
    # discovery is over before the late topic exists, and whatever it or the paused one
    # would write is on disk well within 0.5 s (they flush every 0.1 s)
    time.sleep(0.5)
    late = node.create_publisher(String, f"{topic}/late", KEEP_ALL)
    time.sleep(0.5)
    publish_all(early, 10)
    publish_all(late, 10)
    time.sleep(0.5)
    code, _out, err = paused.finish()
    assert code == 0 and "Wait for recording: Press SPACE to start." in err
    assert blind.finish()[0] == 0
    for bag in ("paused", "blind"):
        with Reader(tmp_path / bag) as reader:
            assert reader.message_count == 0


def test_types_unknown_here_are_recorded_and_played_as_bytes(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, listener: Any, topic: str
) -> None:
    from ros2lite.bag.definitions import type_ref

    alien = type_ref("alien_msgs/msg/Probe", "RIHS01_" + "5a" * 32)
    pub = node.create_publisher(alien, topic, KEEP_ALL)
    rec = recording(tmp_path / "bag", "--topics", topic)
    wait_until(lambda: subscribed(ros_context, topic), timeout=20)
    blobs = [bytes([0, 1, 0, 0, i, i, i, i]) for i in range(5)]
    for blob in blobs:
        pub.publish(blob)
    wait_until(lambda: on_disk(tmp_path / "bag") == 5, timeout=20)
    code, _out, err = rec.finish()
    assert code == 0, err
    with Reader(tmp_path / "bag") as bag:
        meta = bag.topic(topic)
        assert meta is not None and meta.type == "alien_msgs/msg/Probe"
        assert meta.type_description_hash == "RIHS01_" + "5a" * 32
        assert [m for _, m, _ in bag] == blobs  # no definition anywhere: bytes
    node.destroy_publisher(pub)
    lst = listener(topic, alien, raw=True)
    wait_until(lambda: subscribed(ros_context, topic))
    result = play(str(tmp_path / "bag"))
    assert result.returncode == 0, result.stderr
    wait_until(lambda: len(lst.messages) == 5)
    assert lst.messages == blobs


def test_use_sim_time_stamps_with_clock(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, topic: str
) -> None:
    clock_type = get_interface("rosgraph_msgs/msg/Clock")
    clock = node.create_publisher(clock_type, "/clock", 10)
    pub = node.create_publisher(String, topic, KEEP_ALL)
    rec = recording(tmp_path / "bag", "--topics", topic, "--use-sim-time")
    sim = clock_type()
    sim.clock.sec = 1000

    def tick() -> bool:
        clock.publish(sim)
        return subscribed(ros_context, topic)

    wait_until(tick, timeout=20, interval=0.05)
    for _ in range(5):
        clock.publish(sim)
        time.sleep(0.05)
    publish_all(pub, 5)
    wait_until(lambda: on_disk(tmp_path / "bag") == 5, timeout=20)
    code, _out, err = rec.finish()
    assert code == 0, err
    assert "use_sim_time set, waiting for /clock before starting recording..." in err
    with Reader(tmp_path / "bag") as bag:
        stamps = [t for _, _, t in bag]
    assert len(stamps) == 5 and all(t == 1000 * 10**9 for t in stamps)


def test_topic_types_hidden_topics_and_qos_overrides(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, topic: str
) -> None:
    overrides = tmp_path / "qos.yaml"
    overrides.write_text(
        f"{topic}/typed:\n  reliability: best_effort\n  history: keep_last\n  depth: 7\n"
    )
    Int32 = get_interface("std_msgs/msg/Int32")
    typed = node.create_publisher(Int32, f"{topic}/typed", KEEP_ALL)
    hidden = node.create_publisher(String, f"{topic}/_hidden", KEEP_ALL)
    other = node.create_publisher(String, f"{topic}/other", KEEP_ALL)
    Bool = get_interface("std_msgs/msg/Bool")
    excluded = node.create_publisher(Bool, f"{topic}/_flag", KEEP_ALL)  # matches -e
    rec = recording(
        tmp_path / "bag",
        "--topic-types",
        "std_msgs/msg/Int32",
        "--exclude-topic-types",
        "std_msgs/msg/Bool",
        "-e",
        f"^{topic}/_",
        "--include-hidden-topics",
        "--qos-profile-overrides-path",
        str(overrides),
    )
    wait_until(lambda: subscribed(ros_context, f"{topic}/_hidden"), timeout=20)
    wait_until(lambda: subscribed(ros_context, f"{topic}/typed"), timeout=20)
    from ros2lite.graph import snapshot
    from ros2lite.qos import ReliabilityPolicy

    def overridden() -> bool:
        # a snapshot is one liveliness query, and a peer's query can miss a token of another
        # peer (the recorder is one): ask again rather than trust a single one
        subs = [
            e
            for e in snapshot(ros_context.session, ros_context.domain_id)
            if e.kind.value == "MS" and e.topic_name == f"{topic}/typed"
        ]
        return bool(subs) and all(
            s.qos.reliability == ReliabilityPolicy.BEST_EFFORT and s.qos.depth == 7 for s in subs
        )

    wait_until(overridden, timeout=20)
    for i in range(5):
        typed.publish(Int32(data=i))
    publish_all(hidden, 5)
    publish_all(other, 5)
    for _ in range(5):
        excluded.publish(Bool(data=True))
    wait_until(lambda: on_disk(tmp_path / "bag", f"{topic}/typed") == 5, timeout=20)
    wait_until(lambda: on_disk(tmp_path / "bag", f"{topic}/_hidden") == 5, timeout=20)
    code, _out, err = rec.finish()
    assert code == 0, err
    with Reader(tmp_path / "bag") as bag:
        assert sorted(t.name for t in bag.topics) == [f"{topic}/_hidden", f"{topic}/typed"]
        assert [m.data for t, m, _ in bag if t.endswith("typed")] == list(range(5))
    bad = tmp_path / "bad.yaml"
    bad.write_text("/x:\n  colour: red\n")
    result = run_process(
        "bag",
        "record",
        "-a",
        "--qos-profile-overrides-path",
        str(bad),
        "-o",
        str(tmp_path / "never"),
    )
    assert (result.code, result.err) == (
        1,
        "[ERROR] [ros2bag]: Unexpected key `colour` for QoS profile.\n",
    )


def test_sigint_under_load_keeps_a_gapless_prefix(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, topic: str
) -> None:
    import threading

    pub = node.create_publisher(String, topic, KEEP_ALL)
    rec = recording(tmp_path / "bag", "--topics", topic)
    wait_until(lambda: subscribed(ros_context, topic), timeout=20)
    stop = threading.Event()
    sent: list[str] = []

    def flood() -> None:
        i = 0
        while not stop.is_set():
            text = f"{i}"
            pub.publish(String(data=text))
            sent.append(text)
            i += 1
            if i % 200 == 0:
                time.sleep(0.001)

    thread = threading.Thread(target=flood, daemon=True)
    thread.start()
    wait_until(lambda: on_disk(tmp_path / "bag") > 100, timeout=20)  # recording under load
    code, _out, err = rec.finish(signal.SIGINT)  # while messages are still pouring in
    stop.set()
    thread.join(5)
    assert code == 0, err
    with Reader(tmp_path / "bag") as bag:
        got = [m.data for _, m, _ in bag]
    assert len(got) > 100
    assert got == sent[: len(got)]  # everything received up to the stop, no gaps


def test_services_are_recorded_from_their_introspection_events(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any
) -> None:
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.qos import qos_profile_system_default
    from ros2lite.service_introspection import ServiceIntrospectionState

    add = get_interface("example_interfaces/srv/AddTwoInts")
    service = node.create_service(add, "/rec_add", lambda rq, rs: add.Response(sum=rq.a + rq.b))
    client = node.create_client(add, "/rec_add")
    other = node.create_service(add, "/rec_other", lambda rq, rs: rs)
    for end in (service, client, other):
        end.configure_introspection(
            node.get_clock(), qos_profile_system_default, ServiceIntrospectionState.CONTENTS
        )
    events = "/rec_add/_service_event"
    seen: list[Any] = []
    node.create_subscription(f"{add._TYPE_NAME}_Event", events, seen.append, 10)
    rec = recording(tmp_path / "bag", "--services", "/rec_add")
    wait_until(lambda: subscribed(ros_context, events, count=2), timeout=20)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    future = client.call_async(add.Request(a=20, b=22))
    executor.spin_until_future_complete(future, timeout_sec=10)
    assert future.result().sum == 42
    executor.spin_until(lambda: len(seen) == 4, 10)  # the recorder hears them as we do
    executor.shutdown()
    code, _out, err = rec.finish(signal.SIGINT)
    assert code == 0, err
    with Reader(tmp_path / "bag") as bag:
        assert [t.name for t in bag.topics] == [events]  # /rec_other is not asked for
        assert bag.topic(events).type == "example_interfaces/srv/AddTwoInts_Event"  # type: ignore[union-attr]
        got = [m for _, m, _ in bag]
    assert sorted(e.info.event_type for e in got) == [0, 1, 2, 3]
    assert {r.sum for e in got for r in e.response} == {42}


STRING_HASH = "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18"


def test_a_hostile_topic_name_is_skipped_and_recording_goes_on(
    tmp_path: Path, node: Any, ros_context: Any, recording: Any, topic: str, alien_session: Any
) -> None:
    """R-W12: one liveliness token with an invalid topic name stopped `bag record -a` at
    start (exit 1) or ended its discovery (nothing more recorded)."""
    domain = os.environ["ROS_DOMAIN_ID"]

    def hostile(name: str) -> Any:
        key = (
            f"@ros2_lv/{domain}/{os.urandom(16).hex()}/0/0/MP/%/%/ctl/%{name}/"
            f"std_msgs::msg::dds_::String_/{STRING_HASH}/::,10:,:,:,,"
        )
        return alien_session.liveliness().declare_token(key)

    before = hostile("t0\x1b[2J")
    rec = recording(tmp_path / "bag", "-a", "-p", "50")
    first = node.create_publisher(String, f"{topic}/first", KEEP_ALL)
    wait_until(lambda: subscribed(ros_context, f"{topic}/first"), timeout=20)
    during = hostile("t1 bad")
    late = node.create_publisher(String, f"{topic}/late", KEEP_ALL)
    wait_until(lambda: subscribed(ros_context, f"{topic}/late"), timeout=20)
    publish_all(first, 10, "first")
    publish_all(late, 10, "late")
    for name in (f"{topic}/first", f"{topic}/late"):  # -a records /rosout too
        wait_until(lambda: on_disk(tmp_path / "bag", name) == 10, timeout=20)  # noqa: B023
    code, _out, err = rec.finish()
    before.undeclare()
    during.undeclare()
    assert code == 0, err
    assert "Not recording topic '/t0\\x1b[2J': not a valid topic name" in err
    assert "Not recording topic '/t1 bad': not a valid topic name" in err
    assert "\x1b" not in err
    with Reader(tmp_path / "bag") as bag:
        counts = {
            t.topic_metadata.name: t.message_count for t in bag.metadata.topics_with_message_count
        }
    assert counts[f"{topic}/first"] == 10 and counts[f"{topic}/late"] == 10
