"""QoS overrides through parameters: declared read-only per policy, taken from overrides,
checked by the options' callback."""

from __future__ import annotations

from typing import Any

import pytest

from ros2lite.node import Node
from ros2lite.parameter import Parameter
from ros2lite.qos import HistoryPolicy, QoSPolicyKind, QoSProfile, ReliabilityPolicy
from ros2lite.qos_overriding_options import (
    InvalidQosOverridesError,
    QosCallbackResult,
    QoSOverridingOptions,
)


def test_overrides_reach_the_endpoint(ros_context: Any) -> None:
    node = Node(
        'overridden',
        context=ros_context,
        parameter_overrides=[
            Parameter('qos_overrides./chatter.publisher.reliability', value='best_effort'),
            Parameter('qos_overrides./chatter.publisher.depth', value=3),
        ],
    )
    ours = QoSProfile(depth=10)
    pub = node.create_publisher(
        'std_msgs/msg/String',
        'chatter',
        ours,
        qos_overriding_options=QoSOverridingOptions.with_default_policies(),
    )
    assert (pub.qos_profile.reliability, pub.qos_profile.depth) == (
        ReliabilityPolicy.BEST_EFFORT,
        3,
    )
    assert ours.depth == 10  # the caller's profile is left alone
    declared = node.get_parameters_by_prefix('qos_overrides')
    assert declared['/chatter.publisher.history'].value == 'keep_last'
    assert node.describe_parameter('qos_overrides./chatter.publisher.depth').read_only


def test_the_callback_may_refuse(ros_context: Any) -> None:
    def keep_all_only(qos: QoSProfile) -> Any:
        ok = qos.history == HistoryPolicy.KEEP_ALL
        return QosCallbackResult(successful=ok, reason='' if ok else 'keep all, please')

    node = Node('picky', context=ros_context)
    options = QoSOverridingOptions([QoSPolicyKind.HISTORY], callback=keep_all_only, entity_id='one')
    with pytest.raises(InvalidQosOverridesError, match='keep all, please'):
        node.create_subscription(
            'std_msgs/msg/String', 'x', lambda m: None, 10, qos_overriding_options=options
        )
    assert node.has_parameter('qos_overrides./x.subscription_one.history')
