"""QoS overrides through parameters (rclpy's `qos_overriding_options`).

A publisher or subscription created with `qos_overriding_options=QoSOverridingOptions(...)`
declares a read-only parameter per chosen policy, named
`qos_overrides.<topic>.<publisher|subscription>[_<id>].<policy>`; a value given for it at
start-up (`-p`, params file, parameter_overrides) replaces the code's choice, and an optional
callback may refuse the resulting profile.
"""

from __future__ import annotations

import enum
from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, cast

from ros2lite.duration import Duration
from ros2lite.exceptions import ParameterAlreadyDeclaredException, Ros2liteError
from ros2lite.interfaces import get_interface
from ros2lite.qos import (
    DurabilityPolicy,
    HistoryPolicy,
    LivelinessPolicy,
    QoSPolicyKind,
    QoSProfile,
    ReliabilityPolicy,
)

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces.msg import SetParametersResult
    from ros2lite.node_interface import NodeInterface
    from ros2lite.parameter import Parameter

__all__ = [
    'InvalidQosOverridesError',
    'QoSOverridingOptions',
    'QoSPolicyKind',
    'QosCallbackResult',
    'qos_with_overrides',
]

#: what a validation callback returns (rclpy uses SetParametersResult)
QosCallbackResult: type[SetParametersResult] = get_interface(
    'rcl_interfaces/msg/SetParametersResult'
)
QosCallbackType = Callable[[QoSProfile], 'SetParametersResult']

_DURATIONS = {
    QoSPolicyKind.DEADLINE,
    QoSPolicyKind.LIFESPAN,
    QoSPolicyKind.LIVELINESS_LEASE_DURATION,
}
_ENUMS: dict[
    QoSPolicyKind,
    type[DurabilityPolicy] | type[HistoryPolicy] | type[LivelinessPolicy] | type[ReliabilityPolicy],
] = {
    QoSPolicyKind.DURABILITY: DurabilityPolicy,
    QoSPolicyKind.HISTORY: HistoryPolicy,
    QoSPolicyKind.LIVELINESS: LivelinessPolicy,
    QoSPolicyKind.RELIABILITY: ReliabilityPolicy,
}


class InvalidQosOverridesError(Ros2liteError):
    """The overridden profile was refused by the options' callback."""


class QoSOverridingOptions:
    """Which policies may be overridden, an optional validation callback, and an id that
    tells apart several entities of one topic in one node."""

    def __init__(
        self,
        policy_kinds: Iterable[QoSPolicyKind],
        *,
        callback: QosCallbackType | None = None,
        entity_id: str | None = None,
    ) -> None:
        self.policy_kinds = list(policy_kinds)
        self.callback = callback
        self.entity_id = entity_id

    @classmethod
    def with_default_policies(
        cls, *, callback: QosCallbackType | None = None, entity_id: str | None = None
    ) -> QoSOverridingOptions:
        """History, depth and reliability: what rclpy offers by default."""
        return cls(
            [QoSPolicyKind.HISTORY, QoSPolicyKind.DEPTH, QoSPolicyKind.RELIABILITY],
            callback=callback,
            entity_id=entity_id,
        )


def qos_with_overrides(
    entity_type: type,
    node: NodeInterface,
    topic: str,
    qos: QoSProfile | int,
    options: QoSOverridingOptions | None,
) -> QoSProfile:
    """The profile a new publisher or subscription of `node` gets: `qos` (a depth is a
    KEEP_LAST profile of that depth), with the override parameters `options` asks for declared
    and applied to a copy (the caller's profile stays as it was)."""
    from ros2lite.runtime.endpoint import as_qos

    profile = as_qos(qos)
    if options is not None and options.policy_kinds:
        profile = profile.replace()
        _declare_qos_parameters(entity_type, node, node.resolve_topic_name(topic), profile, options)
    return profile


def _entity_type_str(entity_type: type) -> str:
    from ros2lite.publisher import Publisher
    from ros2lite.subscription import Subscription

    if issubclass(entity_type, Publisher):
        return 'publisher'
    if issubclass(entity_type, Subscription):
        return 'subscription'
    raise TypeError(f'QoS overrides are for publishers and subscriptions, not {entity_type}')


def _allowed(entity_type_str: str) -> set[QoSPolicyKind]:
    allowed = {
        QoSPolicyKind.DURABILITY,
        QoSPolicyKind.DEADLINE,
        QoSPolicyKind.LIVELINESS,
        QoSPolicyKind.RELIABILITY,
        QoSPolicyKind.HISTORY,
        QoSPolicyKind.DEPTH,
        QoSPolicyKind.LIVELINESS_LEASE_DURATION,
    }
    if entity_type_str == 'publisher':
        allowed.add(QoSPolicyKind.LIFESPAN)
    return allowed


def _get_qos_policy_parameter(qos: QoSProfile, policy: QoSPolicyKind) -> int | str:
    """The parameter value of one policy of `qos` (short key, depth, or nanoseconds)."""
    value: object = getattr(qos, policy.name.lower())
    if isinstance(value, Duration):
        return value.nanoseconds
    if isinstance(value, enum.Enum):
        return value.name.lower()  # the policy's short key
    return int(cast(int, value))  # depth


def _override_qos_policy_with_param(
    qos: QoSProfile, policy: QoSPolicyKind, param: Parameter
) -> None:
    value: object = param.value
    if policy in _DURATIONS:
        value = Duration(nanoseconds=cast(int, value))
    elif policy in _ENUMS:
        value = _ENUMS[policy].from_short_key(str(value))
    setattr(qos, policy.name.lower(), value)


def _declare_qos_parameters(
    entity_type: type,
    node: NodeInterface,
    topic_name: str,
    qos: QoSProfile,
    options: QoSOverridingOptions,
) -> None:
    """Declare the override parameters of one entity and apply their values to `qos`
    (changed in place); InvalidQosOverridesError if the callback refuses the result."""
    from ros2lite.parameters.store import descriptor

    kind = _entity_type_str(entity_type)
    suffix = '' if options.entity_id is None else f'_{options.entity_id}'
    allowed = _allowed(kind)
    about = f'for {kind} `{topic_name}` with id `{options.entity_id}`'
    for policy in options.policy_kinds:
        if policy not in allowed:
            continue
        policy_name = policy.name.lower()
        name = f'qos_overrides.{topic_name}.{kind}{suffix}.{policy_name}'
        try:
            param = node.declare_parameter(
                name,
                _get_qos_policy_parameter(qos, policy),
                descriptor(description=f'{policy_name} {about}', read_only=True),
            )
        except ParameterAlreadyDeclaredException:
            param = node.get_parameter(name)
        _override_qos_policy_with_param(qos, policy, param)
    if options.callback is not None:
        result = options.callback(qos)
        if not result.successful:
            raise InvalidQosOverridesError(
                f'Provided QoS overrides {about}, are not valid: {result.reason}'
            )
