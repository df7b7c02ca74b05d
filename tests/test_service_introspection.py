"""Service introspection: which events clients and services publish, with what in them,
and switching it off and on at run time."""

from __future__ import annotations

import threading
from typing import Any

import pytest

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface
from ros2lite.node import Node
from ros2lite.qos import qos_profile_system_default
from ros2lite.service_introspection import (
    ServiceEventType,
    ServiceIntrospectionState,
    event_to_dict,
    format_event,
    state_from_name,
)
from tests.spinning import spin_until, wait_matched

AddTwoInts = get_interface('example_interfaces/srv/AddTwoInts')
Event = get_interface('example_interfaces/srv/AddTwoInts_Event')
REQUEST_SENT, REQUEST_RECEIVED, RESPONSE_SENT, RESPONSE_RECEIVED = ServiceEventType


def add(request: Any, response: Any) -> Any:
    response.sum = request.a + request.b
    return response


@pytest.fixture
def pair(ros_context: Any) -> Any:
    node = Node('introspected', context=ros_context, enable_rosout=False)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    events: list[Any] = []
    node.create_subscription(Event, '/intro_add/_service_event', events.append, 100)
    service = node.create_service(AddTwoInts, '/intro_add', add)
    client = node.create_client(AddTwoInts, '/intro_add')
    yield node, executor, service, client, events
    executor.shutdown()
    node.destroy_node()


def call(executor: Any, client: Any, a: int, b: int) -> Any:
    future = client.call_async(AddTwoInts.Request(a=a, b=b))
    executor.spin_until_future_complete(future, timeout_sec=10)
    return future.result()


def test_four_events_with_contents_or_metadata(pair: Any) -> None:
    node, executor, service, client, events = pair
    service.configure_introspection(
        node.get_clock(), qos_profile_system_default, ServiceIntrospectionState.CONTENTS
    )
    client.configure_introspection(
        node.get_clock(), qos_profile_system_default, ServiceIntrospectionState.METADATA
    )
    pub = service._introspection.publisher
    wait_matched(pub)
    assert call(executor, client, 2, 3).sum == 5
    spin_until(executor, lambda: len(events) == 4)
    by_type = {ServiceEventType(e.info.event_type): e for e in events}
    assert set(by_type) == set(ServiceEventType)
    # one request: one sequence number and the client's GID in all four
    assert {e.info.sequence_number for e in events} == {1}
    assert {bytes(e.info.client_gid) for e in events} == {client._gid[:16]}
    # the service sends contents, the client metadata only
    assert [(r.a, r.b) for r in by_type[REQUEST_RECEIVED].request] == [(2, 3)]
    assert [r.sum for r in by_type[RESPONSE_SENT].response] == [5]
    for kind in (REQUEST_SENT, RESPONSE_RECEIVED):
        assert (len(by_type[kind].request), len(by_type[kind].response)) == (0, 0)
    stamps = [e.info.stamp.sec * 10**9 + e.info.stamp.nanosec for e in events]
    assert all(s > 0 for s in stamps)


def test_off_stops_and_the_topic_goes(pair: Any) -> None:
    node, executor, service, client, events = pair
    service.configure_introspection(
        node.get_clock(), qos_profile_system_default, ServiceIntrospectionState.METADATA
    )
    wait_matched(service._introspection.publisher)
    assert node.count_publishers('/intro_add/_service_event') == 1
    call(executor, client, 1, 1)
    spin_until(executor, lambda: len(events) == 2)  # the service's two
    service.configure_introspection(
        node.get_clock(), qos_profile_system_default, ServiceIntrospectionState.OFF
    )
    assert service._introspection is None
    client.configure_introspection(
        node.get_clock(), qos_profile_system_default, ServiceIntrospectionState.CONTENTS
    )
    wait_matched(client._introspection.publisher)
    call(executor, client, 4, 5)
    spin_until(executor, lambda: len(events) == 4)
    # after OFF only the client reports, and it now sends contents
    assert [ServiceEventType(e.info.event_type) for e in events[2:]] == [
        REQUEST_SENT,
        RESPONSE_RECEIVED,
    ]
    assert events[3].response[0].sum == 9 and events[3].info.sequence_number == 2


def test_synchronous_call_reports_its_response(pair: Any) -> None:
    node, executor, _service, client, events = pair
    client.configure_introspection(
        node.get_clock(), qos_profile_system_default, ServiceIntrospectionState.CONTENTS
    )
    wait_matched(client._introspection.publisher)
    spinner = threading.Thread(target=lambda: executor.spin_until(lambda: len(events) >= 2, 10))
    spinner.start()
    assert client.call(AddTwoInts.Request(a=7, b=8), timeout_sec=10).sum == 15
    spinner.join()
    assert [ServiceEventType(e.info.event_type) for e in events] == [
        REQUEST_SENT,
        RESPONSE_RECEIVED,
    ]
    assert events[1].response[0].sum == 15


def test_rendering_and_state_names() -> None:
    info = get_interface('service_msgs/msg/ServiceEventInfo')(
        event_type=2, client_gid=list(range(16)), sequence_number=7
    )
    event = Event(info=info, response=[AddTwoInts.Response(sum=3)])
    assert event_to_dict(event)['info']['event_type'] == 'RESPONSE_SENT'
    text = format_event(event)
    assert text.startswith('info:\n  event_type: RESPONSE_SENT\n  stamp:\n    sec: 0\n')
    assert text.endswith('sequence_number: 7\nrequest: []\nresponse:\n- sum: 3\n')
    # as ros2cli's service echo --flow-style: mappings in block style, sequences in flow style
    flow = format_event(event, flow_style=True)
    assert flow.startswith('info:\n  event_type: RESPONSE_SENT\n  stamp:\n    sec: 0\n')
    assert f'  client_gid: {list(range(16))}\n' in flow
    assert flow.endswith('request: []\nresponse: [{sum: 3}]\n')
    short = format_event(event, no_arr=True)
    assert "  client_gid: '<array type: uint8[16]>'\n" in short
    assert (
        "response: '<sequence type: example_interfaces/srv/AddTwoInts_Response[1], length: 1>'"
        in short
    )
    assert format_event(event, csv=True) == '2,0,0,' + ','.join(map(str, range(16))) + ',7,,3'
    assert state_from_name('contents') == ServiceIntrospectionState.CONTENTS
    with pytest.raises(ValueError, match='must be one of'):
        state_from_name('everything')
