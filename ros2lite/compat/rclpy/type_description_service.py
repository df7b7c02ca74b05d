"""rclpy.type_description_service."""

from ros2lite.type_description_service import (
    START_TYPE_DESCRIPTION_SERVICE_PARAM,
    TypeDescriptionService,
)

__all__ = ['START_TYPE_DESCRIPTION_SERVICE_PARAM', 'TypeDescriptionService']
