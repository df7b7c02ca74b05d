from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ros2lite.qos import QoSProfile
from ros2lite.transport import keys as k
from ros2lite.transport.keys import Entity, EntityKind, parse_token
from ros2lite.transport.qos import decode_qos

STRING_HASH = "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18"
ADD_HASH = "RIHS01_e118de6bf5eeb66a2491b5bda11202e7b68f198d6f67922cf30364858239c81a"

# Reference §2.3, verbatim.
NN_LISTENER = "@ros2_lv/0/aac3178e146ba6f1fc6e6a4085e77f21/0/0/NN/%/%/listener"
MS_LISTENER = (
    "@ros2_lv/0/aac3178e146ba6f1fc6e6a4085e77f21/0/10/MS/%/%/listener/%chatter/"
    f"std_msgs::msg::dds_::String_/{STRING_HASH}/::,10:,:,:,,"
)
SS_ADD = (
    "@ros2_lv/0/f9980ee0495eaafb3e38f0d19e2eae12/0/10/SS/%/%/add_two_ints_server/%add_two_ints/"
    f"example_interfaces::srv::dds_::AddTwoInts_/{ADD_HASH}/::,10:,:,:,,"
)
MP_TALKER = (
    "@ros2_lv/0/8b20917502ee955ac4476e0266340d5c/0/10/MP/%/%robot1/talker/%robot1%chatter/"
    f"std_msgs::msg::dds_::String_/{STRING_HASH}/::,7:,:,:,,"
)


def test_build_reference_tokens() -> None:
    assert k.node_token(0, "aac3178e146ba6f1fc6e6a4085e77f21", 0, "/", "listener") == NN_LISTENER
    assert (
        k.endpoint_token(
            0,
            "aac3178e146ba6f1fc6e6a4085e77f21",
            0,
            10,
            EntityKind.SUBSCRIPTION,
            "/",
            "listener",
            "/chatter",
            "std_msgs/msg/String",
            STRING_HASH,
            QoSProfile(depth=10),
        )
        == MS_LISTENER
    )
    assert (
        k.endpoint_token(
            0,
            "f9980ee0495eaafb3e38f0d19e2eae12",
            0,
            10,
            "SS",
            "/",
            "add_two_ints_server",
            "/add_two_ints",
            "example_interfaces/srv/AddTwoInts",
            ADD_HASH,
            QoSProfile(depth=10),
        )
        == SS_ADD
    )
    assert (
        k.endpoint_token(
            0,
            "8b20917502ee955ac4476e0266340d5c",
            0,
            10,
            EntityKind.PUBLISHER,
            "/robot1",
            "talker",
            "/robot1/chatter",
            "std_msgs::msg::dds_::String_",
            STRING_HASH,
            QoSProfile(depth=7),
        )
        == MP_TALKER
    )


def test_parse_reference_tokens() -> None:
    nn = parse_token(NN_LISTENER)
    assert nn == Entity(
        0, "aac3178e146ba6f1fc6e6a4085e77f21", 0, 0, EntityKind.NODE, "/", "/", "listener"
    )
    assert nn.is_node and nn.node_fqn == "/listener"
    mp = parse_token(MP_TALKER)
    assert mp is not None
    assert (mp.zid, mp.nid, mp.eid, mp.kind) == (
        "8b20917502ee955ac4476e0266340d5c",
        0,
        10,
        EntityKind.PUBLISHER,
    )
    assert (mp.enclave, mp.namespace, mp.node_name, mp.node_fqn) == (
        "/",
        "/robot1",
        "talker",
        "/robot1/talker",
    )
    assert mp.topic_name == "/robot1/chatter"
    assert mp.type_name == "std_msgs/msg/String"
    assert mp.dds_type_name == "std_msgs::msg::dds_::String_"
    assert mp.type_hash == STRING_HASH
    assert mp.qos is not None and mp.qos.depth == 7
    ss = parse_token(SS_ADD)
    assert ss is not None and ss.kind is EntityKind.SERVICE
    assert ss.type_name == "example_interfaces/srv/AddTwoInts"
    for token in (NN_LISTENER, MS_LISTENER, SS_ADD, MP_TALKER):
        parsed = parse_token(token, strict=True)
        assert parsed is not None and parsed.to_token() == token


def test_fourteenth_chunk_is_tolerated() -> None:
    token = MP_TALKER + "/backends:cpu:meta;gpu:x"
    parsed = parse_token(token)
    assert parsed is not None
    assert parsed.extra == ("backends:cpu:meta;gpu:x",)
    assert parsed.qos == decode_qos("::,7:,:,:,,")


@pytest.mark.parametrize(
    "key",
    [
        "",
        "chatter",
        "@ros2_lv/0/zid/0/0/NN/%/%",  # too short
        "@ros2_lv/x/zid/0/0/NN/%/%/n",  # domain not a number
        "@ros2_lv/0/zid/a/0/NN/%/%/n",
        "@ros2_lv/0/zid/0/0/XX/%/%/n",  # unknown kind
        "@ros2_lv/0//0/0/NN/%/%/n",  # empty zid
        "@ros2_lv/0/zid/0/1/MP/%/%/n/%t",  # endpoint without type/hash/qos
        "@other/0/zid/0/0/NN/%/%/n",
    ],
)
def test_garbage_tokens(key: str) -> None:
    assert parse_token(key) is None
    with pytest.raises(ValueError, match="liveliness token"):
        parse_token(key, strict=True)


def test_bad_qos_chunk_is_lenient_unless_strict() -> None:
    token = MP_TALKER.rsplit("/", 1)[0] + "/garbage"
    parsed = parse_token(token)
    assert parsed is not None and parsed.qos is None and parsed.qos_chunk == "garbage"
    with pytest.raises(ValueError, match="QoS chunk"):
        parse_token(token, strict=True)


def test_data_keys() -> None:
    # Reference §1 examples.
    assert k.topic_key(0, "/chatter", "std_msgs/msg/String", STRING_HASH) == (
        f"0/chatter/std_msgs::msg::dds_::String_/{STRING_HASH}"
    )
    assert k.topic_key(0, "/robot1/chatter", "std_msgs/msg/String", STRING_HASH) == (
        f"0/robot1/chatter/std_msgs::msg::dds_::String_/{STRING_HASH}"
    )
    assert k.topic_key(2, "/add_two_ints", "example_interfaces/srv/AddTwoInts", ADD_HASH) == (
        f"2/add_two_ints/example_interfaces::srv::dds_::AddTwoInts_/{ADD_HASH}"
    )
    assert k.topic_key(0, "/x", "a/msg/B", "TypeHashNotSupported").endswith("/TypeHashNotSupported")
    with pytest.raises(ValueError):
        k.topic_key(0, "/", "std_msgs/msg/String", STRING_HASH)
    with pytest.raises(ValueError):
        k.topic_key(0, "/x", "std_msgs/msg/String", "")


@pytest.mark.parametrize(
    ("ros", "dds"),
    [
        ("std_msgs/msg/String", "std_msgs::msg::dds_::String_"),
        ("example_interfaces/srv/AddTwoInts", "example_interfaces::srv::dds_::AddTwoInts_"),
        (
            "example_interfaces/action/Fibonacci_SendGoal",
            "example_interfaces::action::dds_::Fibonacci_SendGoal_",
        ),
        (
            "example_interfaces/action/Fibonacci_FeedbackMessage",
            "example_interfaces::action::dds_::Fibonacci_FeedbackMessage_",
        ),
        ("action_msgs/srv/CancelGoal", "action_msgs::srv::dds_::CancelGoal_"),
    ],
)
def test_type_names(ros: str, dds: str) -> None:
    assert k.dds_type_name(ros) == dds
    assert k.dds_type_name(dds) == dds
    assert k.ros_type_name(dds) == ros
    assert k.ros_type_name(ros) == ros


@pytest.mark.parametrize("bad", ["String", "std_msgs/String", "std_msgs/foo/String", "a//b"])
def test_bad_type_names(bad: str) -> None:
    with pytest.raises(ValueError, match="type name"):
        k.dds_type_name(bad)


def test_mangling_and_prefix() -> None:
    assert k.mangle("/robot1/chatter") == "%robot1%chatter"
    assert k.demangle("%robot1%chatter") == "/robot1/chatter"
    assert k.liveliness_subscription_key(42) == "@ros2_lv/42/**"
    with pytest.raises(ValueError, match="empty"):
        k.node_token(0, "zid", 0, "", "n")
    with pytest.raises(ValueError, match="node_token"):
        k.endpoint_token(0, "z", 0, 1, "NN", "/", "n", "/t", "a/msg/B", "h", QoSProfile(depth=10))


_NUMBER = st.one_of(st.just(''), st.integers(0, 2**64 + 5).map(str), st.text(max_size=4))


@settings(max_examples=300, deadline=None)
@given(st.lists(_NUMBER, min_size=11, max_size=11), st.sampled_from(['MP', 'MS', 'SS', 'SC']))
def test_no_qos_chunk_raises(numbers: list[str], kind: str) -> None:
    """Whatever numbers a peer writes into a token's QoS chunk (rmw_zenoh reads each as a
    uint64), parsing gives an entity or None, never an exception."""
    n = numbers
    chunk = f'{n[0]}:{n[1]}:{n[2]},{n[3]}:{n[4]},{n[5]}:{n[6]},{n[7]}:{n[8]},{n[9]},{n[10]}'
    key = (
        f'@ros2_lv/0/{"ab" * 16}/0/1/{kind}/%/%/node/%topic/std_msgs::msg::dds_::String_/'
        f'RIHS01_{"0" * 64}/{chunk}'
    )
    entity = parse_token(key)
    if entity is not None and entity.qos is not None:
        assert entity.qos.deadline.nanoseconds <= 2**63 - 1
