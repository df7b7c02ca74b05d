"""rclpy.parameter_event_handler."""

from ros2lite.parameter_event_handler import (
    ParameterCallbackHandle,
    ParameterEventCallbackHandle,
    ParameterEventHandler,
)

__all__ = ['ParameterCallbackHandle', 'ParameterEventCallbackHandle', 'ParameterEventHandler']
