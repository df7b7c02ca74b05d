"""A node's ~/get_type_description: descriptions (and sources) of the types it uses, checked
against the RIHS01 hash; other types refused."""

from __future__ import annotations

from typing import Any

from ros2lite.executors import SingleThreadedExecutor
from ros2lite.interfaces import get_interface, type_hash
from ros2lite.node import Node
from ros2lite.parameter import Parameter

GetTypeDescription = get_interface('type_description_interfaces/srv/GetTypeDescription')


def test_descriptions_of_types_in_use(ros_context: Any) -> None:
    node = Node('described', context=ros_context)
    node.create_publisher('geometry_msgs/msg/PoseStamped', 'pose', 1)
    client = node.create_client(GetTypeDescription, '/described/get_type_description')
    executor = SingleThreadedExecutor(context=ros_context)
    executor.add_node(node)

    def ask(name: str, hash_: str = '') -> Any:
        request = GetTypeDescription.Request(type_name=name, type_hash=hash_)
        future = client.call_async(request)
        executor.spin_until_future_complete(future, 10)
        return future.result()

    assert client.wait_for_service(10)
    got = ask('geometry_msgs/msg/PoseStamped', type_hash('geometry_msgs/msg/PoseStamped'))
    assert got.successful
    description = got.type_description
    assert description.type_description.type_name == 'geometry_msgs/msg/PoseStamped'
    referenced = [d.type_name for d in description.referenced_type_descriptions]
    assert 'geometry_msgs/msg/Pose' in referenced and 'std_msgs/msg/Header' in referenced
    sources = {s.type_name: s for s in got.type_sources}
    assert 'Pose pose' in sources['geometry_msgs/msg/PoseStamped'].raw_file_contents
    assert not ask('std_msgs/msg/String').successful  # not used by this node
    wrong = ask('geometry_msgs/msg/PoseStamped', 'RIHS01_' + '0' * 64)
    assert not wrong.successful and 'mismatch' in wrong.failure_reason


def test_the_parameter_turns_it_off(ros_context: Any) -> None:
    node = Node(
        'undescribed',
        context=ros_context,
        parameter_overrides=[Parameter('start_type_description_service', value=False)],
    )
    assert node.count_services('/undescribed/get_type_description') == 0
    assert node.describe_parameter('start_type_description_service').read_only
