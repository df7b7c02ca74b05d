"""rclpy.topic_endpoint_info."""

from ros2lite.topic_endpoint_info import TopicEndpointInfo, TopicEndpointTypeEnum

__all__ = ['TopicEndpointInfo', 'TopicEndpointTypeEnum']
