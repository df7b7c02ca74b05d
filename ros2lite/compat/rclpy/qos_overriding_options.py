"""rclpy.qos_overriding_options."""

from ros2lite.qos_overriding_options import (
    InvalidQosOverridesError,
    QosCallbackResult,
    QoSOverridingOptions,
    QoSPolicyKind,
    _declare_qos_parameters,
    _get_qos_policy_parameter,
)

__all__ = [
    'InvalidQosOverridesError',
    'QoSOverridingOptions',
    'QoSPolicyKind',
    'QosCallbackResult',
    '_declare_qos_parameters',
    '_get_qos_policy_parameter',
]
