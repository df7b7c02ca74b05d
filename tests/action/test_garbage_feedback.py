"""Garbage on an action's feedback and status topics: the goal goes on to its result."""

from __future__ import annotations

import struct
import time
from typing import Any

from ros2lite.msgs.action_msgs.msg import GoalStatus  # type: ignore[attr-defined]
from ros2lite.msgs.example_interfaces.action import Fibonacci  # type: ignore[attr-defined]
from tests.action.fixtures import Fixture
from tests.spinning import wait_until


def test_garbage_feedback_and_status_do_not_end_the_goal(fx: Fixture, alien_session: Any) -> None:
    fx.server()
    client = fx.client()
    feedback: list[Any] = []
    handle = fx.wait(client.send_goal_async(Fibonacci.Goal(order=4), feedback.append))
    wait_until(lambda: len(feedback) == 3)
    att = struct.pack('<qqB', 1, time.time_ns(), 16) + b'\xee' * 16
    for sub in (client._feedback_sub, client._status_sub):
        pub = alien_session.declare_publisher(sub._ep.key)
        for junk in (b'', b'\x00\x01\x00\x00\xff\xff\xff\xff', b'garbage'):
            pub.put(junk, attachment=att)
        pub.undeclare()
    wait_until(
        lambda: all(
            s.bad_samples is not None and s.bad_samples.total >= 1
            for s in (client._feedback_sub, client._status_sub)
        ),
        timeout=15,
    )
    fx.release.set()
    response = fx.wait(handle.get_result_async())
    assert response.status == GoalStatus.STATUS_SUCCEEDED
    assert list(response.result.sequence) == [0, 1, 1, 2, 3]
