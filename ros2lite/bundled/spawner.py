"""The body of the spawn entry points (`gazebo_ros spawn_entity.py`, `ros_gz_sim create`):
find the robot's URDF (a topic, a file, a parameter, a string), send it to the running 2D
world (`ros2lite.sim.spawn`'s spawn topic) and wait for the world's answer, as the real
spawners wait for Gazebo's spawn service."""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from ros2lite.exceptions import Ros2liteError
from ros2lite.runtime.arguments import remove_ros_args


class SpawnFailed(Ros2liteError):
    """The robot could not be spawned: one line for the user."""


@dataclass(frozen=True)
class Order:
    """What a spawner's command line asks: the entity, where its URDF comes from (one of
    topic, file, text, param), its pose and namespace, and how long to wait for the world."""

    name: str
    topic: str = ''
    file: str = ''
    text: str = ''
    param: str = ''
    x: float = 0.0
    y: float = 0.0
    yaw: float = 0.0
    namespace: str = ''
    timeout: float = 30.0


def spawn(node_name: str, order: Order) -> None:
    """Send the robot to the world and return once it is there; SpawnFailed says why not."""
    import json

    import ros2lite
    from ros2lite.msgs.std_msgs.msg import String
    from ros2lite.node import Node
    from ros2lite.qos import DurabilityPolicy, QoSProfile
    from ros2lite.sim.spawn import SPAWN_TOPIC, SPAWNED_TOPIC, SpawnRequest

    latched = QoSProfile(depth=10, durability=DurabilityPolicy.TRANSIENT_LOCAL)
    node = Node(node_name)
    log = node.get_logger()
    source, name, timeout = order, order.name, order.timeout
    pose = (order.x, order.y, math.atan2(math.sin(order.yaw), math.cos(order.yaw)))
    deadline = time.monotonic() + timeout

    def spin_until(done: object, what: str) -> None:
        while not callable(done) or not done():
            if time.monotonic() > deadline:
                raise SpawnFailed(f'{node_name}: timed out after {timeout:g} s {what}')
            ros2lite.spin_once(node, timeout_sec=0.05)

    try:
        if source.file:
            try:
                text = Path(source.file).read_text()
            except OSError as e:
                raise SpawnFailed(f'cannot read {source.file}: {e.strerror}') from None
        elif source.text:
            text = source.text
        elif source.param:
            value = node.declare_parameter(source.param, '').value
            if not isinstance(value, str) or not value:
                raise SpawnFailed(f'parameter {source.param!r} holds no robot description')
            text = value
        else:
            got: list[str] = []
            topic = source.topic
            node.create_subscription(String, topic, lambda m: got.append(m.data), latched)
            log.info(f'Waiting for the robot description on topic {topic}')
            spin_until(lambda: bool(got), f'waiting for a message on {topic}')
            text = got[0]
        name = name or _robot_name(text)
        request = SpawnRequest(name, text, *pose, namespace=order.namespace)
        answers: list[dict[str, object]] = []
        warned: list[bool] = []

        def on_answer(msg: String) -> None:
            # any peer can publish on the answer topic: what is not JSON is not our answer
            try:
                answer = json.loads(msg.data)
            except (ValueError, RecursionError):
                if not warned:
                    warned.append(True)
                    log.warn(f'ignoring an answer on {SPAWNED_TOPIC} that is not JSON')
                return
            if isinstance(answer, dict) and answer.get('id') == request.id:
                answers.append(answer)

        node.create_subscription(String, SPAWNED_TOPIC, on_answer, latched)
        pub = node.create_publisher(String, SPAWN_TOPIC, 10)
        log.info(f'Waiting for the 2D world ({SPAWN_TOPIC})')
        spin_until(lambda: pub.get_subscription_count() > 0, f'waiting for {SPAWN_TOPIC}')
        pub.publish(String(data=request.to_json()))
        spin_until(lambda: bool(answers), 'waiting for the world to answer')
        answer = answers[0]
        if not answer.get('ok'):
            raise SpawnFailed(f'spawning {name!r} failed: {answer.get("message")}')
        log.info(f'Spawned {name!r} at ({pose[0]:g}, {pose[1]:g}), yaw {pose[2]:g}')
    finally:
        node.destroy_node()


def _robot_name(text: str) -> str:
    """The `<robot name=...>` of a URDF, for a spawner given no entity name."""
    from ros2lite.urdf import UrdfError
    from ros2lite.urdf.parse import read_xml

    try:  # the hardened reader: no DTD or entities, bounded in size
        return read_xml(text, 'robot description').get('name', '') or 'robot'
    except UrdfError as e:
        raise SpawnFailed(str(e)) from None


def run_spawner(node_name: str, parse: Callable[[list[str]], Order], args: list[str] | None) -> int:
    """Run a spawner whose `parse(argv)` reads its command line; its exit status."""
    from ros2lite.bundled.runner import run_main

    argv = sys.argv[1:] if args is None else args
    order = parse(remove_ros_args(argv))
    return run_main(lambda: spawn(node_name, order), args)
