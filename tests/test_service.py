"""Service servers on rmw_zenoh's wire, checked against a bare zenoh peer that speaks the
protocol by hand (rmw_zenoh.md §5): a complete queryable on the service key, replies that echo
the request's sequence number and client GID, malformed requests dropped, SS tokens."""

from __future__ import annotations

import json
import struct
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.graph import snapshot
from ros2lite.msgs.example_interfaces.srv import AddTwoInts
from ros2lite.node import Node
from ros2lite.parameter import Parameter
from ros2lite.transport.keys import EntityKind
from tests.spinning import wait_until

HASHES = json.loads(
    (Path(__file__).parent / 'interfaces' / 'data' / 'rihs01_jazzy.json').read_text()
)
ADD_HASH = HASHES['example_interfaces/srv/AddTwoInts']
ADD_TYPE = 'example_interfaces::srv::dds_::AddTwoInts_'
CLIENT_GID = bytes(range(0x30, 0x40))


def header(seq: int, ts: int, gid: bytes) -> bytes:
    return struct.pack('<qqB', seq, ts, 16) + gid


@pytest.fixture
def served(ros_context: Any) -> Iterator[tuple[Node, list[Any]]]:
    """An add_two_ints server spun on a background thread; yields (node, requests seen)."""
    node = Node('adder', context=ros_context)
    seen: list[Any] = []

    def add(request: Any, response: Any) -> Any:
        seen.append(request)
        response.sum = request.a + request.b
        return response

    node.create_service(AddTwoInts, 'add_two_ints', add)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    thread = threading.Thread(target=executor.spin, daemon=True)
    thread.start()
    yield node, seen
    executor.shutdown()
    thread.join(timeout=5)


def alien_call(session: Any, domain: int, payload: bytes, attachment: bytes | None) -> list[Any]:
    import zenoh

    key = f'{domain}/add_two_ints/{ADD_TYPE}/{ADD_HASH}'
    replies = session.get(
        key,
        payload=payload,
        attachment=attachment,
        target=zenoh.QueryTarget.ALL_COMPLETE,
        consolidation=zenoh.ConsolidationMode.NONE,
        timeout=10,
    )
    return [r.ok for r in replies if r.ok is not None]


def test_reply_echoes_sequence_number_and_client_gid(
    served: Any, alien_session: Any, ros_context: Any
) -> None:
    request = b'\x00\x01\x00\x00' + struct.pack('<qq', 20, 22)
    before = time.time_ns()
    wait_until(
        lambda: any(
            e.kind == EntityKind.SERVICE
            for e in snapshot(ros_context.session, ros_context.domain_id)
        )
    )
    (reply,) = alien_call(
        alien_session, ros_context.domain_id, request, header(42, time.time_ns(), CLIENT_GID)
    )
    assert reply.payload.to_bytes() == b'\x00\x01\x00\x00' + struct.pack('<q', 42)
    seq, stamp, n = struct.unpack_from('<qqB', reply.attachment.to_bytes())
    assert (seq, n) == (42, 16)
    assert reply.attachment.to_bytes()[17:] == CLIENT_GID
    assert before <= stamp <= time.time_ns()
    assert served[1][-1] == AddTwoInts.Request(a=20, b=22)


def test_requests_without_a_valid_attachment_are_dropped(
    served: Any, alien_session: Any, ros_context: Any
) -> None:
    request = b'\x00\x01\x00\x00' + struct.pack('<qq', 1, 2)
    wait_until(
        lambda: any(
            e.kind == EntityKind.SERVICE
            for e in snapshot(ros_context.session, ros_context.domain_id)
        )
    )
    assert alien_call(alien_session, ros_context.domain_id, request, None) == []
    assert (
        alien_call(
            alien_session, ros_context.domain_id, request, header(-1, time.time_ns(), CLIENT_GID)
        )
        == []
    )
    assert (
        alien_call(
            alien_session, ros_context.domain_id, b'\x00\x01', header(1, time.time_ns(), CLIENT_GID)
        )
        == []
    )  # undecodable CDR
    assert served[1] == []
    # and the server still answers a good one afterwards
    assert (
        len(
            alien_call(
                alien_session, ros_context.domain_id, request, header(2, time.time_ns(), CLIENT_GID)
            )
        )
        == 1
    )


def test_server_and_client_tokens(ros_context: Any) -> None:
    node = Node(
        'tokens',
        namespace='/ns',
        context=ros_context,
        start_parameter_services=False,
        parameter_overrides=[Parameter('start_type_description_service', value=False)],
    )
    node.create_service(AddTwoInts, 'add', lambda req, resp: resp)
    node.create_client(AddTwoInts, '~/private_add')

    def found() -> list[Any]:
        return [
            e
            for e in snapshot(ros_context.session, ros_context.domain_id)
            if e.node_name == 'tokens' and e.kind in (EntityKind.SERVICE, EntityKind.CLIENT)
        ]

    entities = wait_until(lambda: len(found()) == 2 and found())
    by_kind = {e.kind: e for e in entities}
    server, client = by_kind[EntityKind.SERVICE], by_kind[EntityKind.CLIENT]
    assert server.topic_name == '/ns/add' and client.topic_name == '/ns/tokens/private_add'
    for e in (server, client):
        assert e.type_name == 'example_interfaces/srv/AddTwoInts' and e.type_hash == ADD_HASH
    assert '/SS/' in server.to_token() and '/SC/' in client.to_token()


def test_alien_server_called_by_our_client(alien_session: Any, ros_context: Any) -> None:
    """A queryable written from the reference; our client's requests carry seq 1, 2, … and the
    client's GID, and the reply is matched back to the right call."""
    import zenoh

    domain = ros_context.domain_id
    key = f'{domain}/alien_add/{ADD_TYPE}/{ADD_HASH}'
    seen: list[tuple[int, bytes]] = []

    def serve(query: Any) -> None:
        with query:
            att = query.attachment.to_bytes()
            seq, _ts, _n = struct.unpack_from('<qqB', att)
            seen.append((seq, att[17:]))
            a, b = struct.unpack_from('<qq', query.payload.to_bytes(), 4)
            query.reply(
                key,
                b'\x00\x01\x00\x00' + struct.pack('<q', a * b),
                attachment=header(seq, time.time_ns(), att[17:]),
            )

    queryable = alien_session.declare_queryable(key, zenoh.handlers.Callback(serve), complete=True)
    token = alien_session.liveliness().declare_token(
        f'@ros2_lv/{domain}/{alien_session.info.zid()}/0/1/SS/%/%/alien/%alien_add/'
        f'example_interfaces%srv%AddTwoInts/{ADD_HASH}/::,10:,:,:,,'
    )
    try:
        node = Node('caller', context=ros_context)
        client = node.create_client(AddTwoInts, '/alien_add')
        assert client.wait_for_service(timeout_sec=10)
        assert client.call(AddTwoInts.Request(a=6, b=7), timeout_sec=10).sum == 42
        assert client.call(AddTwoInts.Request(a=2, b=5), timeout_sec=10).sum == 10
        assert [s for s, _ in seen] == [1, 2]
        assert {g for _, g in seen} == {client._gid}
    finally:
        token.undeclare()
        queryable.undeclare()
