"""One publisher or subscription of a topic as the graph reports it (rclpy's
`TopicEndpointInfo`), printed the way `ros2 topic info -v` prints it."""

from __future__ import annotations

import enum
from collections.abc import Iterable, Sequence

from ros2lite.qos import HistoryPolicy, QoSProfile, qos_profile_unknown

__all__ = ['TopicEndpointInfo', 'TopicEndpointTypeEnum', 'format_gid']


class TopicEndpointTypeEnum(enum.IntEnum):
    """Which side of a topic an endpoint is."""

    INVALID = 0
    PUBLISHER = 1
    SUBSCRIPTION = 2


def format_gid(gid: Iterable[int]) -> str:
    """rclpy's dotted lower-case hex, e.g. `01.0f.2a.…`."""
    return '.'.join(f'{b:02x}' for b in gid)


_FIELDS = (
    'node_name',
    'node_namespace',
    'topic_type',
    'topic_type_hash',
    'endpoint_type',
    'endpoint_gid',
    'qos_profile',
)


class TopicEndpointInfo:
    """Node, type (and its RIHS01 hash), side, GID and QoS of one endpoint."""

    __slots__ = (
        '_endpoint_type',
        'endpoint_gid',
        'node_name',
        'node_namespace',
        'qos_profile',
        'topic_type',
        'topic_type_hash',
    )

    def __init__(
        self,
        node_name: str = '',
        node_namespace: str = '',
        topic_type: str = '',
        topic_type_hash: str = '',
        endpoint_type: TopicEndpointTypeEnum = TopicEndpointTypeEnum.INVALID,
        endpoint_gid: bytes | Sequence[int] = (),
        qos_profile: QoSProfile | None = None,
    ) -> None:
        self.node_name = node_name
        self.node_namespace = node_namespace
        self.topic_type = topic_type
        self.topic_type_hash = topic_type_hash
        self.endpoint_type = endpoint_type
        self.endpoint_gid = endpoint_gid
        self.qos_profile: QoSProfile = (
            qos_profile if qos_profile is not None else qos_profile_unknown
        )

    @property
    def endpoint_type(self) -> TopicEndpointTypeEnum:
        """Publisher or subscription."""
        return self._endpoint_type

    @endpoint_type.setter
    def endpoint_type(self, value: TopicEndpointTypeEnum | int | str) -> None:
        """Set from the enum, its number or its name (as rclpy accepts)."""
        if isinstance(value, str):
            value = TopicEndpointTypeEnum[value]
        self._endpoint_type = TopicEndpointTypeEnum(value)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, TopicEndpointInfo):
            return NotImplemented
        return all(getattr(self, f) == getattr(other, f) for f in _FIELDS)

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        fields = ', '.join(f'{f}={getattr(self, f)!r}' for f in _FIELDS)
        return f'TopicEndpointInfo({fields})'

    def __str__(self) -> str:
        qos = self.qos_profile
        history = qos.history.name
        if qos.history == HistoryPolicy.KEEP_LAST:
            history += f' ({qos.depth})'
        return '\n'.join(
            [
                f'Node name: {self.node_name}',
                f'Node namespace: {self.node_namespace}',
                f'Topic type: {self.topic_type}',
                f'Topic type hash: {self.topic_type_hash or "INVALID"}',
                f'Endpoint type: {self.endpoint_type.name}',
                f'GID: {format_gid(self.endpoint_gid)}',
                'QoS profile:',
                f'  Reliability: {qos.reliability.name}',
                f'  History (Depth): {history}',
                f'  Durability: {qos.durability.name}',
                f'  Lifespan: {qos.lifespan}',
                f'  Deadline: {qos.deadline}',
                f'  Liveliness: {qos.liveliness.name}',
                f'  Liveliness lease duration: {qos.liveliness_lease_duration}',
            ]
        )
