"""What an action looks like on the wire: the five sub-entities' liveliness tokens with
their own types, RIHS01 hashes (from the Jazzy reference table) and QoS; and the hashes of
the bundled action_tutorials_interfaces checked against rosbags."""

from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Any

from ros2lite.action import ActionClient, ActionServer
from ros2lite.node import Node

TABLE = json.loads(
    (Path(__file__).parents[1] / 'interfaces' / 'data' / 'rihs01_jazzy.json').read_text()
)
FIB = 'example_interfaces/action/Fibonacci'


def tokens_of(alien: Any, domain: int, zid: str, nid: int) -> set[str]:
    import zenoh

    replies = alien.liveliness().get(
        f'@ros2_lv/{domain}/**', zenoh.handlers.FifoChannel(4096), timeout=5
    )
    keys = {str(r.ok.key_expr) for r in replies if r.ok is not None}
    return {k for k in keys if k.split('/')[2:4] == [zid, str(nid)]}


def expected_tokens(node: Node, kinds: tuple[str, str]) -> set[str]:
    """Endpoint tokens from their kind on: `<kind>/%/<ns>/<node>/<name>/<type>/<hash>/<qos>`."""
    service, topic = kinds
    name = node.get_name()
    parts = [
        (
            service,
            'send_goal',
            'example_interfaces::action::dds_::Fibonacci_SendGoal_',
            TABLE[FIB + '_SendGoal'],
            '::,10:,:,:,,',
        ),
        (
            service,
            'cancel_goal',
            'action_msgs::srv::dds_::CancelGoal_',
            TABLE['action_msgs/srv/CancelGoal'],
            '::,10:,:,:,,',
        ),
        (
            service,
            'get_result',
            'example_interfaces::action::dds_::Fibonacci_GetResult_',
            TABLE[FIB + '_GetResult'],
            '::,10:,:,:,,',
        ),
        (
            topic,
            'feedback',
            'example_interfaces::action::dds_::Fibonacci_FeedbackMessage_',
            TABLE[FIB + '_FeedbackMessage'],
            '::,10:,:,:,,',
        ),
        (
            topic,
            'status',
            'action_msgs::msg::dds_::GoalStatusArray_',
            TABLE['action_msgs/msg/GoalStatusArray'],
            ':1:,1:,:,:,,',
        ),
    ]
    return {
        f'{kind}/%/%robot/{name}/%robot%fib%_action%{entity}/{dds}/{hsh}/{qos}'
        for kind, entity, dds, hsh, qos in parts
    }


def test_sub_entities_tokens(ros_context: Any, alien_session: Any) -> None:
    d, zid = ros_context.domain_id, ros_context.zid
    server_node = Node('wire_server', namespace='/robot', context=ros_context, enable_rosout=False)
    client_node = Node('wire_client', namespace='/robot', context=ros_context, enable_rosout=False)
    server = ActionServer(server_node, FIB, 'fib', lambda handle: None)
    client = ActionClient(client_node, FIB, 'fib')

    def endpoint_tokens(node: Node) -> set[str]:
        # drop the prefix up to the entity id, and the node's own parameter services
        found = tokens_of(alien_session, d, zid, node.node_id)
        return {k.split('/', 5)[5] for k in found if '_action' in k}

    want_server = expected_tokens(server_node, ('SS', 'MP'))
    want_client = expected_tokens(client_node, ('SC', 'MS'))
    deadline = time.monotonic() + 15
    while (endpoint_tokens(server_node), endpoint_tokens(client_node)) != (
        want_server,
        want_client,
    ):
        assert time.monotonic() < deadline, (endpoint_tokens(server_node), want_server)
        time.sleep(0.1)
    # the client's own graph view learns of the server's tokens on its own schedule (the
    # alien session above may have seen them first)
    assert client.wait_for_server(timeout_sec=15)
    server.destroy()
    client.destroy()
    deadline = time.monotonic() + 15
    while endpoint_tokens(server_node) or endpoint_tokens(client_node):
        assert time.monotonic() < deadline
        time.sleep(0.1)


def test_bundled_tutorial_hashes_match_rosbags() -> None:
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    from ros2lite import interfaces

    store = get_typestore(Stores.ROS2_JAZZY)
    base = 'action_tutorials_interfaces/action/Fibonacci'
    store.register(
        {
            **get_types_from_msg('int32 order', base + '_Goal'),
            **get_types_from_msg('int32[] sequence', base + '_Result'),
            **get_types_from_msg('int32[] partial_sequence', base + '_Feedback'),
            **get_types_from_msg(
                f'unique_identifier_msgs/UUID goal_id\n{base}_Feedback feedback',
                base + '_FeedbackMessage',
            ),
        }
    )
    for suffix in ('_Goal', '_Result', '_Feedback', '_FeedbackMessage'):
        assert interfaces.type_hash(base + suffix) == store.hash_rihs01(base + suffix)
