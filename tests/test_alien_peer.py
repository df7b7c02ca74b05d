"""Interop with a peer that is *not* ros2lite: a bare zenoh session that speaks rmw_zenoh by
hand, the way rmw_zenoh_cpp does on the wire.

Every key, token, CDR payload and attachment on the alien side is spelled out literally from
the rmw_zenoh reference (no ros2lite helpers), so this test is an independent oracle for our
transport, graph and client library.
"""

from __future__ import annotations

import json
import struct
import threading
import time
from pathlib import Path
from typing import Any

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.node import Node
from ros2lite.subscription import MessageInfo
from tests.spinning import spin_until

STRING_TYPE = 'std_msgs::msg::dds_::String_'
STRING_HASH = 'RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18'
LOG_TYPE = 'rcl_interfaces::msg::dds_::Log_'
LOG_HASH = 'RIHS01_e28ce254ca8abc06abf92773b74602cdbf116ed34fbaf294fb9f81da9f318eac'
ALIEN_GID = bytes(range(0xA0, 0xB0))


def cdr_string(text: str) -> bytes:
    """std_msgs/String in XCDR1 little-endian: header, uint32 length incl. NUL, bytes, NUL."""
    raw = text.encode() + b'\x00'
    return b'\x00\x01\x00\x00' + struct.pack('<I', len(raw)) + raw


def parse_cdr_string(data: bytes) -> str:
    assert data[:4] == b'\x00\x01\x00\x00'
    (n,) = struct.unpack_from('<I', data, 4)
    assert data[8 + n - 1] == 0 and len(data) >= 8 + n
    return data[8 : 8 + n - 1].decode()


def attachment(seq: int, ts: int, gid: bytes) -> bytes:
    return struct.pack('<qqB', seq, ts, 16) + gid


def test_ros2lite_sees_and_hears_the_alien(ros_context: Any, alien_session: Any) -> None:
    d = ros_context.domain_id
    zid = str(alien_session.info.zid())
    ns, name, topic = '%alien_ns', 'alien_node', '%alien_ns%alien_chatter'
    nn = alien_session.liveliness().declare_token(f'@ros2_lv/{d}/{zid}/0/0/NN/%/{ns}/{name}')
    mp = alien_session.liveliness().declare_token(
        f'@ros2_lv/{d}/{zid}/0/1/MP/%/{ns}/{name}/{topic}/{STRING_TYPE}/{STRING_HASH}/2::,7:,:,:,,'
    )
    data_key = f'{d}/alien_ns/alien_chatter/{STRING_TYPE}/{STRING_HASH}'
    alien_pub = alien_session.declare_publisher(data_key)
    try:
        node = Node('lite_node', context=ros_context)
        deadline = time.monotonic() + 15
        # the node's token and its publisher's token arrive one after the other: wait for both
        while ('alien_node', '/alien_ns') not in node.get_node_names_and_namespaces() or (
            '/alien_ns/alien_chatter',
            ['std_msgs/msg/String'],
        ) not in node.get_topic_names_and_types():
            assert time.monotonic() < deadline, node.get_topic_names_and_types()
            time.sleep(0.05)
        [info] = node.get_publishers_info_by_topic('/alien_ns/alien_chatter')
        assert (info.node_name, info.node_namespace) == ('alien_node', '/alien_ns')
        assert info.qos_profile is not None and info.qos_profile.depth == 7
        assert info.qos_profile.reliability.name == 'BEST_EFFORT'
        assert node.get_publisher_names_and_types_by_node('alien_node', '/alien_ns') == [
            ('/alien_ns/alien_chatter', ['std_msgs/msg/String'])
        ]

        typed: list[str] = []
        raw: list[tuple[bytes, MessageInfo]] = []
        node.create_subscription(
            'std_msgs/msg/String', '/alien_ns/alien_chatter', lambda m: typed.append(m.data), 10
        )
        node.create_subscription(
            'std_msgs/msg/String',
            '/alien_ns/alien_chatter',
            lambda b, i: raw.append((b, i)),
            10,
            raw=True,
        )
        ex = SingleThreadedExecutor(context=ros_context)
        ex.add_node(node)
        seq = 0

        def sent_and_heard() -> bool:
            nonlocal seq
            seq += 1
            alien_pub.put(
                cdr_string(f'alien {seq}'), attachment=attachment(seq, time.time_ns(), ALIEN_GID)
            )
            ex.spin_once(timeout_sec=0.05)
            return bool(typed) and bool(raw)

        spin_until(ex, sent_and_heard, timeout=15)
        first_seq = int(typed[0].split()[1])
        assert typed[0] == f'alien {first_seq}'
        data, msg_info = raw[0]
        assert parse_cdr_string(data) == f'alien {msg_info.publication_sequence_number}'
        assert msg_info.publisher_gid == ALIEN_GID
        assert abs(msg_info.source_timestamp - time.time_ns()) < 5_000_000_000
    finally:
        for entity in (alien_pub, mp, nn):
            entity.undeclare()


def test_alien_hears_ros2lite(ros_context: Any, alien_session: Any) -> None:
    d = ros_context.domain_id
    received: list[tuple[bytes, bytes | None]] = []
    cond = threading.Condition()

    def on_sample(sample: Any) -> None:
        with cond:
            att = sample.attachment
            received.append((sample.payload.to_bytes(), None if att is None else att.to_bytes()))
            cond.notify_all()

    sub = alien_session.declare_subscriber(f'{d}/from_lite/{STRING_TYPE}/{STRING_HASH}', on_sample)
    # the alien announces its subscription, so the ros2lite side can wait for it in the graph
    token = alien_session.liveliness().declare_token(
        f'@ros2_lv/{d}/{alien_session.info.zid()}/0/0/MS/%/%/alien_listener/%from_lite/'
        f'{STRING_TYPE}/{STRING_HASH}/::,10:,:,:,,'
    )
    try:
        node = Node('lite_talker', context=ros_context)
        pub = node.create_publisher('std_msgs/msg/String', 'from_lite', 10)
        deadline = time.monotonic() + 15
        while pub.get_subscription_count() < 1:
            assert time.monotonic() < deadline
            time.sleep(0.02)
        time.sleep(0.1)
        String = pub.msg_type
        before = time.time_ns()
        for i in range(3):
            pub.publish(String(data=f'Hello World: {i}'))
        with cond:
            assert cond.wait_for(lambda: len(received) >= 3, 5)
        after = time.time_ns()
        for i, (payload, att) in enumerate(received):
            assert parse_cdr_string(payload) == f'Hello World: {i}'
            assert att is not None and len(att) == 33
            seq, ts, gid_len = struct.unpack_from('<qqB', att)
            assert (seq, gid_len) == (i + 1, 16)
            assert before <= ts <= after
            assert att[17:] == pub.gid
    finally:
        token.undeclare()
        sub.undeclare()


def test_liveliness_tokens_have_the_rmw_zenoh_shape(ros_context: Any, alien_session: Any) -> None:
    import zenoh

    d = ros_context.domain_id
    node = Node('lite_node', context=ros_context)
    node.create_publisher('std_msgs/msg/String', 'chatter', 7)
    node.create_subscription('std_msgs/msg/String', '/robot1/chatter', lambda m: None, 10)
    zid = ros_context.zid
    assert zid == str(ros_context.session.info.zid())
    hashes = json.loads(
        (Path(__file__).parent / 'interfaces' / 'data' / 'rihs01_jazzy.json').read_text()
    )
    expected = {
        f'@ros2_lv/{d}/{zid}/0/0/NN/%/%/lite_node',
        f'@ros2_lv/{d}/{zid}/0/1/MP/%/%/lite_node/%rosout/{LOG_TYPE}/{LOG_HASH}/:1:,1000:,:10,0:,,',
        # every node publishes /parameter_events and serves the six parameter services…
        f'@ros2_lv/{d}/{zid}/0/2/MP/%/%/lite_node/%parameter_events/'
        'rcl_interfaces::msg::dds_::ParameterEvent_/'
        f"{hashes['rcl_interfaces/msg/ParameterEvent']}/::,1000:,:,:,,",
        *(
            f'@ros2_lv/{d}/{zid}/0/{3 + i}/SS/%/%/lite_node/%lite_node%{service}/'
            f'rcl_interfaces::srv::dds_::{srv}_/{hashes["rcl_interfaces/srv/" + srv]}/'
            '::,1000:,:,:,,'
            for i, (service, srv) in enumerate(
                [
                    ('describe_parameters', 'DescribeParameters'),
                    ('get_parameters', 'GetParameters'),
                    ('get_parameter_types', 'GetParameterTypes'),
                    ('list_parameters', 'ListParameters'),
                    ('set_parameters', 'SetParameters'),
                    ('set_parameters_atomically', 'SetParametersAtomically'),
                ]
            )
        ),
        # and ~/get_type_description, as rcl's nodes do from Jazzy on
        f'@ros2_lv/{d}/{zid}/0/9/SS/%/%/lite_node/%lite_node%get_type_description/'
        'type_description_interfaces::srv::dds_::GetTypeDescription_/'
        f"{hashes['type_description_interfaces/srv/GetTypeDescription']}/::,10:,:,:,,",
        f'@ros2_lv/{d}/{zid}/0/10/MP/%/%/lite_node/%chatter/{STRING_TYPE}/{STRING_HASH}/::,7:,:,:,,',
        f'@ros2_lv/{d}/{zid}/0/11/MS/%/%/lite_node/%robot1%chatter/{STRING_TYPE}/{STRING_HASH}/'
        '::,10:,:,:,,',
    }

    def tokens_of_ours() -> set[str]:
        replies = alien_session.liveliness().get(
            f'@ros2_lv/{d}/**', zenoh.handlers.FifoChannel(1024), timeout=5
        )
        keys = {str(r.ok.key_expr) for r in replies if r.ok is not None}
        return {k for k in keys if f'/{zid}/' in k}

    # the tokens travel to the router asynchronously: wait for the last one, then compare
    deadline = time.monotonic() + 15
    while not (mine := tokens_of_ours()) >= expected and time.monotonic() < deadline:
        time.sleep(0.05)
    assert mine == expected
