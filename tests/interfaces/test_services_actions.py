"""Round trips of every service and action sub-type through CDR."""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from ros2lite import interfaces as I

from .strategies import message

SERVICES = [n for n in I.list_interfaces() if '/srv/' in n]
ACTIONS = [n for n in I.list_interfaces() if '/action/' in n]
SUBTYPES = [s + suffix for s in SERVICES for suffix in ('_Request', '_Response', '_Event')] + [
    a + suffix
    for a in ACTIONS
    for suffix in (
        '_Goal',
        '_Result',
        '_Feedback',
        '_FeedbackMessage',
        '_SendGoal_Request',
        '_SendGoal_Response',
        '_GetResult_Request',
        '_GetResult_Response',
    )
]


def test_counts() -> None:
    assert len(SERVICES) > 40 and len(ACTIONS) >= 4


@pytest.mark.parametrize('name', SUBTYPES)
@settings(max_examples=5, deadline=None, suppress_health_check=list(HealthCheck))
@given(data=st.data())
def test_round_trip(name: str, data: st.DataObject) -> None:
    msg = data.draw(message(name))
    assert I.deserialize(name, I.serialize(msg)) == msg


def test_event_carries_bounded_request() -> None:
    srv = I.get_interface('example_interfaces/srv/AddTwoInts')
    event = srv.Event(request=[srv.Request(a=1, b=2)])
    back = I.deserialize('example_interfaces/srv/AddTwoInts_Event', I.serialize(event))
    assert back.request[0].b == 2 and back.response == []
