"""The node as the parts it is built from use it: a typing Protocol.

A node is made of parts that call back into its public API: the parameter events and
services, the time source, the logger and type-description services, rates and QoS
overrides. node.py makes them, so they cannot import node.py; they take a `NodeInterface`
instead, which :class:`ros2lite.node.Node` is. It names the node's entities, so it stands
beside them on the top level, not in runtime/ under them. Entities ask less of their node
(:class:`ros2lite.runtime.executable.EntityNode`,
:class:`ros2lite.service_introspection.ServiceNode`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Protocol

from ros2lite.service_introspection import ServiceNode

if TYPE_CHECKING:
    from ros2lite.clock import Clock
    from ros2lite.msgs.rcl_interfaces.msg import (
        ListParametersResult,
        ParameterDescriptor,
        ParameterValue,
        SetParametersResult,
    )
    from ros2lite.parameter import AllowableParameterValue, Parameter
    from ros2lite.qos import QoSProfile
    from ros2lite.runtime.endpoint import EndpointOwner
    from ros2lite.service import Service, ServiceCallback
    from ros2lite.service_introspection import IntrospectionMixin
    from ros2lite.subscription import Subscription
    from ros2lite.timer import Timer
    from ros2lite.type_support import MsgT, SrvRequestT, SrvResponseT

__all__ = ['NodeInterface']

# what parameters/store.py calls an OnSetCallback, spelled out: parameters/ stands beside
# this module and imports it, so this module does not import parameters/
OnSetCallback = Callable[[list['Parameter']], 'SetParametersResult']


class NodeInterface(ServiceNode, Protocol):
    """What a node's own parts call of it (rclpy's names and signatures, as far as used)."""

    @property
    def publishers(self) -> Sequence[EndpointOwner]:
        """The node's publishers."""
        ...

    @property
    def subscriptions(self) -> Sequence[EndpointOwner]:
        """The node's subscriptions."""
        ...

    @property
    def services(self) -> Sequence[IntrospectionMixin]:
        """The node's service servers."""
        ...

    @property
    def clients(self) -> Sequence[IntrospectionMixin]:
        """The node's service clients."""
        ...

    def get_fully_qualified_name(self) -> str:
        """Namespace and name, '/ns/name'."""
        ...

    # -- entities ------------------------------------------------------------------------------
    def create_subscription(
        self,
        msg_type: str,
        topic: str,
        callback: Callable[[MsgT], object],
        qos_profile: QoSProfile | int,
    ) -> Subscription[MsgT]:
        """A subscription of the node's to a 'pkg/msg/Name' type."""
        ...

    def destroy_subscription(self, sub: Subscription[MsgT]) -> bool:
        """Withdraw a subscription of the node's."""
        ...

    def create_service(
        self,
        srv_type: str,
        srv_name: str,
        callback: ServiceCallback[SrvRequestT, SrvResponseT],
        *,
        qos_profile: QoSProfile = ...,
    ) -> Service[SrvRequestT, SrvResponseT]:
        """A service server of the node's, of a 'pkg/srv/Name' type."""
        ...

    def destroy_service(self, srv: Service[SrvRequestT, SrvResponseT]) -> bool:
        """Withdraw a service server of the node's."""
        ...

    def create_timer(
        self, timer_period_sec: float, callback: Callable[[], object], *, clock: Clock | None = None
    ) -> Timer:
        """A timer of the node's."""
        ...

    def destroy_timer(self, timer: Timer) -> bool:
        """Cancel a timer of the node's and forget it."""
        ...

    # -- parameters ----------------------------------------------------------------------------
    def declare_parameter(
        self,
        name: str,
        value: AllowableParameterValue | Parameter.Type | ParameterValue = None,
        descriptor: ParameterDescriptor | None = None,
    ) -> Parameter:
        """Declare a parameter (its override, if any, wins)."""
        ...

    def has_parameter(self, name: str) -> bool:
        """Whether the parameter is declared."""
        ...

    def get_parameter(self, name: str) -> Parameter:
        """A declared parameter."""
        ...

    def get_parameter_type(self, name: str) -> Parameter.Type:
        """The type of a declared parameter."""
        ...

    def describe_parameter(self, name: str) -> ParameterDescriptor:
        """The descriptor of a declared parameter."""
        ...

    def list_parameters(self, prefixes: list[str], depth: int) -> ListParametersResult:
        """The names (and prefixes) of the parameters under `prefixes`, to `depth`."""
        ...

    def set_parameters_atomically(self, parameter_list: Sequence[Parameter]) -> SetParametersResult:
        """Set them all, or none."""
        ...

    def add_on_set_parameters_callback(self, callback: OnSetCallback) -> None:
        """Have `callback` accept or refuse every change."""
        ...

    def remove_on_set_parameters_callback(self, callback: OnSetCallback) -> None:
        """Forget a callback of :meth:`add_on_set_parameters_callback`."""
        ...
