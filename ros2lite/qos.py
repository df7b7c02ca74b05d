"""rclpy.qos's names: QoS profiles, policies and presets, as user code imports them.

They are defined once, in :mod:`ros2lite.transport.qos`, next to their wire encoding.
"""

from __future__ import annotations

from ros2lite.duration import Duration
from ros2lite.transport.qos import (
    DurabilityPolicy,
    HistoryPolicy,
    LivelinessPolicy,
    QoSPresetProfiles,
    QoSProfile,
    ReliabilityPolicy,
    qos_profile_action_status_default,
    qos_profile_best_available,
    qos_profile_parameter_events,
    qos_profile_parameters,
    qos_profile_rosout_default,
    qos_profile_sensor_data,
    qos_profile_services_default,
    qos_profile_system_default,
    qos_profile_unknown,
)

__all__ = [
    'DurabilityPolicy',
    'Duration',
    'HistoryPolicy',
    'LivelinessPolicy',
    'QoSPresetProfiles',
    'QoSProfile',
    'ReliabilityPolicy',
    'qos_profile_action_status_default',
    'qos_profile_best_available',
    'qos_profile_parameter_events',
    'qos_profile_parameters',
    'qos_profile_rosout_default',
    'qos_profile_sensor_data',
    'qos_profile_services_default',
    'qos_profile_system_default',
    'qos_profile_unknown',
]
