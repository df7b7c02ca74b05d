"""Publishers on the wire, checked with a plain Zenoh subscriber: the rmw_zenoh data key, the
CDR payload and the 33-byte attachment (sequence from 1, timestamp now, GID of the token)."""

from __future__ import annotations

import struct
import threading
import time
from collections.abc import Iterator
from typing import Any

import pytest

from ros2lite import interfaces
from ros2lite.node import Node
from ros2lite.qos import QoSProfile, ReliabilityPolicy
from tests.spinning import wait_matched

String = interfaces.get_interface('std_msgs/msg/String')
STRING_HASH = 'RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18'


class Tap:
    """A bare zenoh subscriber that records (key, payload, attachment) of every sample."""

    def __init__(self, session: Any, key: str) -> None:
        self.samples: list[tuple[str, bytes, bytes | None]] = []
        self._cond = threading.Condition()
        self._sub = session.declare_subscriber(key, self._on)

    def _on(self, sample: Any) -> None:
        att = sample.attachment
        with self._cond:
            self.samples.append(
                (
                    str(sample.key_expr),
                    sample.payload.to_bytes(),
                    None if att is None else att.to_bytes(),
                )
            )
            self._cond.notify_all()

    def wait(self, n: int, timeout: float = 5.0) -> list[tuple[str, bytes, bytes | None]]:
        return self.wait_for(lambda got: len(got) >= n, timeout)

    def wait_for(
        self, predicate: Any, timeout: float = 5.0
    ) -> list[tuple[str, bytes, bytes | None]]:
        with self._cond:
            assert self._cond.wait_for(lambda: predicate(self.samples), timeout), self.samples
            return list(self.samples)


@pytest.fixture
def bare_session(ros_router: str) -> Iterator[Any]:
    from ros2lite.transport.open import open_session

    session = open_session()
    try:
        yield session
    finally:
        session.close()


@pytest.fixture
def node(ros_context: Any) -> Node:
    return Node('pub_test', namespace='/robot1', context=ros_context)


def test_wire_format(ros_context: Any, node: Node, bare_session: Any) -> None:
    domain = ros_context.domain_id
    key = f'{domain}/robot1/chatter/std_msgs::msg::dds_::String_/{STRING_HASH}'
    tap = Tap(bare_session, key)
    pub = node.create_publisher(String, 'chatter', 7)
    assert pub.topic_name == '/robot1/chatter'
    probe = String(data='probe')
    wait_matched_by_tap(pub, tap, probe)
    probes = pub._seq
    time.sleep(0.1)  # let in-flight probes land
    msgs = [String(data=f'Hello World: {i}') for i in range(3)]
    before = time.time_ns()
    for m in msgs:
        pub.publish(m)
    probe_cdr = interfaces.serialize(probe)
    samples = tap.wait_for(lambda got: len([s for s in got if s[1] != probe_cdr]) == 3)
    samples = [s for s in samples if s[1] != probe_cdr]
    after = time.time_ns()
    token = (
        f'@ros2_lv/{domain}/{ros_context.zid}/{node.node_id}/{pub._ep.entity_id}/MP/%/'
        f'%robot1/pub_test/%robot1%chatter/std_msgs::msg::dds_::String_/{STRING_HASH}/'
        f'::,7:,:,:,,'
    )
    import xxhash

    gid = xxhash.xxh3_128_intdigest(token.encode()).to_bytes(16, 'little')
    assert pub.gid == gid
    for i, (k, payload, att) in enumerate(samples):
        assert k == key
        assert payload == interfaces.serialize(msgs[i])
        assert payload[:4] == b'\x00\x01\x00\x00'
        assert att is not None and len(att) == 33
        seq, ts, n = struct.unpack_from('<qqB', att)
        assert seq == probes + i + 1
        assert before <= ts <= after
        assert n == 16 and att[17:] == gid


def wait_matched_by_tap(pub: Any, tap: Tap, probe: Any, timeout: float = 5.0) -> None:
    """Publish probes until the tap hears one (a bare subscriber has no graph token)."""
    deadline = time.monotonic() + timeout
    while not tap.samples:
        assert time.monotonic() < deadline, 'tap never received anything'
        pub.publish(probe)
        time.sleep(0.05)


def test_sequence_numbers_start_at_one(ros_context: Any, node: Node, bare_session: Any) -> None:
    # the tap exists before the publisher, and the publisher waits for the graph to show a
    # subscription of its own node, so the very first sample is seen
    pub = node.create_publisher(String, 'seq', 10)
    tap = Tap(bare_session, pub._ep.key)
    node.create_subscription(String, 'seq', lambda m: None, 10)
    wait_matched(pub)
    time.sleep(0.1)
    pub.publish(String(data='first'))
    pub.publish(String(data='second'))
    samples = tap.wait(2)
    assert [struct.unpack_from('<q', s[2] or b'')[0] for s in samples] == [1, 2]


def test_wrong_message_type_is_rejected(node: Node) -> None:
    pub = node.create_publisher(String, 'typed_only', 10)
    with pytest.raises(TypeError, match='std_msgs/msg/String'):
        pub.publish(interfaces.get_interface('std_msgs/msg/Int32')(data=1))
    assert pub._seq == 0


def test_properties_and_qos(node: Node) -> None:
    qos = QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT)
    pub = node.create_publisher(String, '~/private', qos)
    assert pub.topic_name == '/robot1/pub_test/private'
    assert pub.msg_type is String
    assert pub.qos_profile == qos
    assert pub.qos_profile.depth == 5
    assert node.create_publisher(String, 'depth_only', 3).qos_profile.depth == 3


def test_subscription_count_follows_the_graph(ros_context: Any, node: Node) -> None:
    pub = node.create_publisher(String, 'counted', 10)
    assert pub.get_subscription_count() == 0
    sub = node.create_subscription(String, 'counted', lambda m: None, 10)
    wait_matched(pub)
    node.destroy_subscription(sub)
    deadline = time.monotonic() + 5
    while pub.get_subscription_count() != 0:
        assert time.monotonic() < deadline
        time.sleep(0.02)
    node.destroy_publisher(pub)
    assert pub not in node.publishers
    with pytest.raises(RuntimeError, match='destroyed'):
        pub.publish(String(data='too late'))
