"""rclpy's TopicEndpointInfo: settable fields, equality, and the text `topic info -v` prints."""

from __future__ import annotations

from ros2lite.qos import QoSProfile
from ros2lite.topic_endpoint_info import TopicEndpointInfo, TopicEndpointTypeEnum


def test_fields_equality_and_text() -> None:
    info = TopicEndpointInfo()
    assert str(info).splitlines()[3:6] == [
        'Topic type hash: INVALID',
        'Endpoint type: INVALID',
        'GID: ',
    ]
    info.node_name = 'n'
    info.endpoint_type = TopicEndpointTypeEnum.SUBSCRIPTION
    info.endpoint_gid = [1, 255]
    info.qos_profile = QoSProfile(depth=7)
    assert info == TopicEndpointInfo(
        node_name='n',
        endpoint_type=TopicEndpointTypeEnum.SUBSCRIPTION,
        endpoint_gid=[1, 255],
        qos_profile=QoSProfile(depth=7),
    )
    text = str(info)
    assert 'Endpoint type: SUBSCRIPTION' in text and 'GID: 01.ff' in text
    assert '  History (Depth): KEEP_LAST (7)' in text
    info.endpoint_type = 'PUBLISHER'  # type: ignore[assignment]  # by name, as a token says
    assert info.endpoint_type is TopicEndpointTypeEnum.PUBLISHER
