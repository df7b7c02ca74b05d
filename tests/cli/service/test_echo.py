"""`service echo` as a real process: the four events of a call with contents, in ros2cli's
YAML; CSV; and the warning when nobody introspects."""

from __future__ import annotations

import threading
from typing import Any

import yaml

from ros2lite.qos import qos_profile_system_default
from ros2lite.service_introspection import ServiceIntrospectionState
from tests.spinning import wait_until


class Echo:
    """A `service echo` process whose stdout is collected line by line as it comes."""

    def __init__(self, processes: Any, *args: str) -> None:
        self.proc = processes.cli('service', 'echo', *args)
        self.processes = processes
        self.lines: list[str] = []
        self.thread = threading.Thread(target=self._read, daemon=True)
        self.thread.start()

    def _read(self) -> None:
        for line in self.proc.stdout:
            self.lines.append(line)

    def text(self) -> str:
        return ''.join(self.lines)

    def stop(self) -> str:
        _out, err = self.processes.stop(self.proc)
        self.thread.join(timeout=5)
        return str(err)


def test_echo_a_call_with_contents(adder: Any, processes: Any) -> None:
    from ros2lite.msgs.example_interfaces.srv import AddTwoInts

    service = next(s for s in adder.services if s.srv_name == '/add_two_ints')
    client = next(c for c in adder.clients if c.srv_name == '/add_two_ints')
    plain = Echo(processes, '/add_two_ints')
    csv = Echo(processes, 'add_two_ints', 'example_interfaces/srv/AddTwoInts', '--csv')
    warning = (
        "No publishers on topic '/add_two_ints/_service_event'; is service introspection on "
        'the client or server enabled?\n'
    )
    wait_until(lambda: plain.lines and csv.lines, timeout=20)
    assert plain.lines == [warning] and csv.lines == [warning]
    for end in (service, client):
        end.configure_introspection(
            adder.get_clock(), qos_profile_system_default, ServiceIntrospectionState.CONTENTS
        )
    # both echo processes subscribed before the introspection publishers came up
    wait_until(lambda: adder.count_subscribers('/add_two_ints/_service_event') == 2)
    for end in (service, client):
        publisher = end._introspection.publisher
        wait_until(lambda p=publisher: p.get_subscription_count() == 2)
    assert client.call(AddTwoInts.Request(a=2, b=3), timeout_sec=10).sum == 5
    wait_until(lambda: plain.text().count('---\n') == 4 and len(csv.lines) == 5, timeout=20)
    plain.stop()
    csv.stop()

    events = [e for e in yaml.safe_load_all(plain.text().removeprefix(warning)) if e]
    assert len(events) == 4
    kinds = {e['info']['event_type']: e for e in events}
    assert set(kinds) == {'REQUEST_SENT', 'REQUEST_RECEIVED', 'RESPONSE_SENT', 'RESPONSE_RECEIVED'}
    gid = list(client._gid[:16])
    for event in events:
        assert list(event) == ['info', 'request', 'response']
        assert list(event['info']) == ['event_type', 'stamp', 'client_gid', 'sequence_number']
        assert event['info']['client_gid'] == gid and event['info']['sequence_number'] == 1
    for kind in ('REQUEST_SENT', 'REQUEST_RECEIVED'):
        assert kinds[kind]['request'] == [{'a': 2, 'b': 3}] and kinds[kind]['response'] == []
    for kind in ('RESPONSE_SENT', 'RESPONSE_RECEIVED'):
        assert kinds[kind]['request'] == [] and kinds[kind]['response'] == [{'sum': 5}]
    # the block style rosidl_runtime_py dumps
    assert (
        '\n  client_gid:\n  - ' in plain.text() and '\nrequest:\n- a: 2\n  b: 3\n' in plain.text()
    )
    rows = sorted(line.rstrip('\n').split(',') for line in csv.lines[1:])
    assert [row[0] for row in rows] == ['0', '1', '2', '3']  # event types, as numbers
    assert rows[0][3:19] == [str(b) for b in gid] and rows[0][19] == '1'


def test_echo_errors(run: Any, adder: Any) -> None:
    unknown = run('service', 'echo', '/no_such_service')
    assert (unknown.code, unknown.err) == (1, 'Could not load the type for the passed service\n')
    bad = run('service', 'echo', '/add_two_ints', 'example_interfaces/srv/Nope')
    assert (bad.code, bad.err) == (
        1,
        "The service type 'example_interfaces/srv/Nope' is invalid\n",
    )


def test_a_sample_that_is_not_the_event_type_is_dropped(
    adder: Any, processes: Any, alien_session: Any
) -> None:
    """Anyone can put bytes on the event topic: one bad sample is reported, the echo goes on."""
    import struct
    import time

    from ros2lite.interfaces import get_interface, serialize, type_hash
    from ros2lite.transport.keys import topic_key

    event_type = 'example_interfaces/srv/AddTwoInts_Event'
    topic = '/add_two_ints/_service_event'
    echo = Echo(processes, '/add_two_ints', 'example_interfaces/srv/AddTwoInts')
    wait_until(lambda: adder.count_subscribers(topic) == 1, timeout=20)
    key = topic_key(adder.context.domain_id, topic, event_type, type_hash(event_type))
    good = get_interface(event_type)()
    good.info.sequence_number = 7
    for seq, payload in enumerate((b'\x00\x01\x00\x00junk', serialize(good)), 1):
        attachment = struct.pack('<qqB', seq, time.time_ns(), 16) + bytes([7]) * 16
        alien_session.put(key, payload, attachment=attachment)
    wait_until(lambda: 'sequence_number: 7' in echo.text(), timeout=20)
    assert echo.proc.poll() is None
    echo.stop()
