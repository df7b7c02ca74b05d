"""The spawners against a hostile graph: an answer topic any peer can publish on carries
something that is not JSON (ignored, the spawner still takes the world's real answer), and a
robot description with a DTD is refused by the hardened reader, in one line."""

from __future__ import annotations

import json
import subprocess
import sys
from typing import Any

import pytest

from tests.bundled.gazebo_ros.test_gazebo_ros import _bot
from tests.spinning import wait_until


@pytest.mark.timeout(90)
def test_a_malformed_answer_is_ignored(ros_context: Any) -> None:
    """A stand-in world: it answers each request with garbage first, then the real answer."""
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.msgs.std_msgs.msg import String
    from ros2lite.node import Node
    from ros2lite.qos import DurabilityPolicy, QoSProfile
    from ros2lite.sim.spawn import SPAWN_TOPIC, SPAWNED_TOPIC, SpawnRequest

    node = Node('fake_world', context=ros_context)
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)
    latched = QoSProfile(depth=10, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    answer_pub = node.create_publisher(String, SPAWNED_TOPIC, latched)
    requests: list[SpawnRequest] = []

    def on_request(msg: String) -> None:
        request = SpawnRequest.from_json(msg.data)
        requests.append(request)
        answer_pub.publish(String(data='{not json'))
        answer_pub.publish(String(data='[' * 100_000))  # too deep for the json module
        answer = {'id': request.id, 'name': request.name, 'ok': True, 'message': ''}
        answer_pub.publish(String(data=json.dumps(answer)))

    node.create_subscription(String, SPAWN_TOPIC, on_request, 10)
    spawner = subprocess.Popen(
        [sys.executable, '-m', 'ros2lite', 'run', 'ros_gz_sim', 'create', '-string', _bot('x'),
         '-name', 'fake_bot'],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
    )  # fmt: skip
    try:
        wait_until(
            lambda: spawner.poll() is not None,
            60,
            step=lambda: executor.spin_once(timeout_sec=0.05),
        )
        out, err = spawner.communicate()
    finally:
        if spawner.poll() is None:
            spawner.kill()
        node.destroy_node()
        executor.shutdown()
    said = out + err
    assert [r.name for r in requests] == ['fake_bot']
    assert spawner.returncode == 0, said
    assert "Spawned 'fake_bot'" in said
    warned = [line for line in said.splitlines() if 'that is not JSON' in line]
    assert len(warned) == 1, said
    assert 'Traceback' not in said


def test_the_robot_name_is_read_by_the_hardened_reader() -> None:
    from ros2lite.bundled.spawner import SpawnFailed, _robot_name

    assert _robot_name('<robot name="my_bot"><link name="a"/></robot>') == 'my_bot'
    entity = '<!DOCTYPE robot [<!ENTITY n "evil">]><robot name="&n;"/>'
    with pytest.raises(SpawnFailed, match='declares a DTD or an entity: refused'):
        _robot_name(entity)
    with pytest.raises(SpawnFailed, match='not well-formed XML'):
        _robot_name('<robot name="a">')
