"""An action server that is *not* ros2lite: a bare zenoh session serving
example_interfaces/action/Fibonacci the way rcl_action over rmw_zenoh_cpp does on the wire.

Keys, tokens, type hashes, attachments and CDR are written out here from the rmw_zenoh
reference (§2, §3, §5, §6), with no ros2lite code, so the client side of ros2lite is checked
against an independent peer. Goals with a negative order are rejected; the others run in a
thread, publishing status and one feedback per step.
"""

from __future__ import annotations

import os
import struct
import threading
import time
from collections.abc import Iterator
from typing import Any

import pytest

SERVER_GID = bytes(range(0x30, 0x40))
FIB = 'example_interfaces::action::dds_::Fibonacci'
# RIHS01 hashes of the sub-types, from the Jazzy reference table
SEND_GOAL_HASH = 'RIHS01_d1a57fb2a4afe8c21e34fb10db206f16ce6729b28531141472df92277c55b557'
GET_RESULT_HASH = 'RIHS01_1b0de0d5d29dc955d92f546706568428632771db13ec84c15ec1c1a59f424a57'
FEEDBACK_HASH = 'RIHS01_c1de71afd52e49a89c53d8262366884185bc0a02f78ce051c4e46b0a7fe59bb2'
CANCEL_HASH = 'RIHS01_573d8b0a534451d7bc2ac8c5ffde8ac14b8593b7001175d0cd6516dcbeb8689a'
STATUS_HASH = 'RIHS01_6c1684b00f177d37438febe6e709fc4e2b0d4248dca4854946f9ed8b30cda83e'
CANCEL_TYPE = 'action_msgs::srv::dds_::CancelGoal_'
STATUS_TYPE = 'action_msgs::msg::dds_::GoalStatusArray_'
SERVICE_QOS = '::,10:,:,:,,'
EXECUTING, CANCELING, SUCCEEDED, CANCELED = 2, 3, 4, 5


class Cdr:
    """Just enough of an XCDR1 little-endian writer: alignment is counted from the body."""

    def __init__(self) -> None:
        self.body = bytearray()

    def put(self, fmt: str, *values: Any) -> Cdr:
        size = struct.calcsize('<' + fmt.lstrip('0123456789')[0])
        self.body += b'\x00' * (-len(self.body) % size)
        self.body += struct.pack('<' + fmt, *values)
        return self

    def raw(self, data: bytes) -> Cdr:
        self.body += data
        return self

    def bytes(self) -> bytes:
        return b'\x00\x01\x00\x00' + bytes(self.body)


def reply_attachment(query_attachment: bytes) -> bytes:
    """Echo the client's sequence number and GID with a fresh timestamp (§3, §5)."""
    seq = struct.unpack_from('<q', query_attachment)[0]
    return struct.pack('<qqB', seq, time.time_ns(), 16) + query_attachment[17:33]


class AlienFibonacciServer:
    def __init__(
        self,
        session: Any,
        domain_id: int,
        action: str = 'alien_fib',
        node: str = 'alien_action_server',
        step: float = 0.05,
    ) -> None:
        import zenoh.ext

        self.session, self.step = session, step
        d, zid = domain_id, str(session.info.zid())
        self.goals: dict[bytes, dict[str, Any]] = {}
        self.lock = threading.Lock()
        self.requests: list[str] = []
        self.closed = False
        self._pub_seq = 0
        base = f'{d}/{action}/_action'
        mangled = '%' + action.replace('/', '%') + '%_action'
        lv = f'@ros2_lv/{d}/{zid}/0'
        self.entities: list[Any] = [session.liveliness().declare_token(f'{lv}/0/NN/%/%/{node}')]
        services = [
            ('send_goal', f'{FIB}_SendGoal_', SEND_GOAL_HASH, self._on_send_goal),
            ('cancel_goal', CANCEL_TYPE, CANCEL_HASH, self._on_cancel),
            ('get_result', f'{FIB}_GetResult_', GET_RESULT_HASH, self._on_get_result),
        ]
        eid = 1
        for name, dds, hsh, cb in services:
            self.entities.append(
                session.declare_queryable(f'{base}/{name}/{dds}/{hsh}', cb, complete=True)
            )
            self.entities.append(
                session.liveliness().declare_token(
                    f'{lv}/{eid}/SS/%/%/{node}/{mangled}%{name}/{dds}/{hsh}/{SERVICE_QOS}'
                )
            )
            eid += 1
        self.feedback = session.declare_publisher(
            f'{base}/feedback/{FIB}_FeedbackMessage_/{FEEDBACK_HASH}'
        )
        self.entities.append(
            session.liveliness().declare_token(
                f'{lv}/{eid}/MP/%/%/{node}/{mangled}%feedback/{FIB}_FeedbackMessage_/'
                f'{FEEDBACK_HASH}/::,10:,:,:,,'
            )
        )
        # transient local status: an advanced publisher with a one-sample cache (§8.3)
        self.status = zenoh.ext.declare_advanced_publisher(
            session,
            f'{base}/status/{STATUS_TYPE}/{STATUS_HASH}',
            cache=zenoh.ext.CacheConfig(1),
            publisher_detection=True,
        )
        self.entities.append(
            session.liveliness().declare_token(
                f'{lv}/{eid + 1}/MP/%/%/{node}/{mangled}%status/{STATUS_TYPE}/{STATUS_HASH}/'
                ':1:,1:,:,:,,'
            )
        )
        self.entities += [self.feedback, self.status]

    def close(self) -> None:
        if self.closed:
            return
        self.closed = True
        with self.lock:  # no goal thread is publishing from here on
            for entity in reversed(self.entities):
                entity.undeclare()

    def _attachment(self) -> bytes:
        self._pub_seq += 1
        return struct.pack('<qqB', self._pub_seq, time.time_ns(), 16) + SERVER_GID

    def _publish_status(self) -> None:
        with self.lock:
            if self.closed:
                return
            cdr = Cdr().put('I', len(self.goals))
            for uuid, goal in self.goals.items():
                cdr.raw(uuid).put('iI', goal['sec'], goal['nanosec']).put('b', goal['status'])
            self.status.put(cdr.bytes(), attachment=self._attachment())

    def _on_send_goal(self, query: Any) -> None:
        self.requests.append('send_goal')
        data = query.payload.to_bytes()
        uuid, order = data[4:20], struct.unpack_from('<i', data, 20)[0]
        now = time.time_ns()
        sec, nanosec = divmod(now, 1_000_000_000)
        accepted = order >= 0
        query.reply(
            query.key_expr,
            Cdr().put('?', accepted).put('iI', sec, nanosec).bytes(),
            attachment=reply_attachment(query.attachment.to_bytes()),
        )
        if accepted:
            with self.lock:
                self.goals[uuid] = {
                    'sec': sec,
                    'nanosec': nanosec,
                    'status': EXECUTING,
                    'order': order,
                    'result': None,
                    'waiting': [],
                    'cancel': False,
                }
            threading.Thread(target=self._execute, args=(uuid,), daemon=True).start()

    def _execute(self, uuid: bytes) -> None:
        self._publish_status()
        goal = self.goals[uuid]
        seq = [0, 1]
        for i in range(1, goal['order']):
            if goal['cancel'] or self.closed:
                break
            seq.append((seq[i] + seq[i - 1]) % 2**31)  # long goals stay int32
            fb = Cdr().raw(uuid).put('I', len(seq)).put(f'{len(seq)}i', *seq)
            with self.lock:
                if not self.closed:
                    self.feedback.put(fb.bytes(), attachment=self._attachment())
            time.sleep(self.step)
        with self.lock:
            goal['status'] = CANCELED if goal['cancel'] else SUCCEEDED
            goal['result'] = seq
            waiting, goal['waiting'] = goal['waiting'], []
        self._publish_status()
        for query in waiting:
            self._reply_result(query, goal)

    def _reply_result(self, query: Any, goal: dict[str, Any]) -> None:
        seq = goal['result']
        cdr = Cdr().put('b', goal['status']).put('I', len(seq)).put(f'{len(seq)}i', *seq)
        query.reply(
            query.key_expr, cdr.bytes(), attachment=reply_attachment(query.attachment.to_bytes())
        )
        query.drop()

    def _on_get_result(self, query: Any) -> None:
        self.requests.append('get_result')
        uuid = query.payload.to_bytes()[4:20]
        with self.lock:
            goal = self.goals.get(uuid)
            if goal is not None and goal['result'] is None:
                goal['waiting'].append(query)  # answered when the goal ends
                return
        if goal is None:  # unknown goal: status UNKNOWN and an empty result
            goal = {'status': 0, 'result': []}
        self._reply_result(query, goal)

    def _on_cancel(self, query: Any) -> None:
        self.requests.append('cancel_goal')
        uuid = query.payload.to_bytes()[4:20]
        with self.lock:
            goal = self.goals.get(uuid)
            ok = goal is not None and goal['result'] is None
            if ok:
                goal['cancel'], goal['status'] = True, CANCELING
        cdr = Cdr().put('b', 0 if ok else 1).put('I', int(ok))
        if ok:
            cdr.raw(uuid).put('iI', goal['sec'], goal['nanosec'])
        query.reply(
            query.key_expr, cdr.bytes(), attachment=reply_attachment(query.attachment.to_bytes())
        )
        if ok:
            self._publish_status()


@pytest.fixture
def alien_server(alien_session: Any) -> Iterator[AlienFibonacciServer]:
    server = AlienFibonacciServer(alien_session, int(os.environ['ROS_DOMAIN_ID']))
    try:
        yield server
    finally:
        server.close()
