"""A node's logger services (`enable_logger_service=True`): `~/get_logger_levels` and
`~/set_logger_levels` (rcl_interfaces), so tools can change a running node's log levels.

Levels are process-wide, as rcutils' are: setting `rcl` through one node sets it for all.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from ros2lite.logging import LoggingSeverity, get_logger_level, set_logger_level

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces.msg import LoggerLevel, SetLoggerLevelsResult
    from ros2lite.msgs.rcl_interfaces.srv import (
        GetLoggerLevels_Request,
        GetLoggerLevels_Response,
        SetLoggerLevels_Request,
        SetLoggerLevels_Response,
    )
    from ros2lite.node_interface import NodeInterface
    from ros2lite.service import Service

    _Services = tuple[
        Service[GetLoggerLevels_Request, GetLoggerLevels_Response],
        Service[SetLoggerLevels_Request, SetLoggerLevels_Response],
    ]

__all__ = ['LoggingService']

_INVALID = 'Failed reason: Invalid logger level.'


class LoggingService:
    """Serves the two logger services on `node`."""

    def __init__(self, node: NodeInterface) -> None:
        name = node.get_name()
        self._node = node
        self._services: _Services | None = (
            node.create_service(
                'rcl_interfaces/srv/GetLoggerLevels', f'{name}/get_logger_levels', self._get
            ),
            node.create_service(
                'rcl_interfaces/srv/SetLoggerLevels', f'{name}/set_logger_levels', self._set
            ),
        )

    def _get(
        self, request: GetLoggerLevels_Request, response: GetLoggerLevels_Response
    ) -> GetLoggerLevels_Response:
        from ros2lite.interfaces import get_interface

        level_msg: type[LoggerLevel] = get_interface('rcl_interfaces/msg/LoggerLevel')
        # the logger's own level, UNSET (0) when none was set for it, as rclpy answers
        response.levels = [
            level_msg(name=name, level=int(get_logger_level(name))) for name in request.names
        ]
        return response

    def _set(
        self, request: SetLoggerLevels_Request, response: SetLoggerLevels_Response
    ) -> SetLoggerLevels_Response:
        from ros2lite.interfaces import get_interface

        result_msg: type[SetLoggerLevelsResult] = get_interface(
            'rcl_interfaces/msg/SetLoggerLevelsResult'
        )
        results = []
        for level in request.levels:
            if level.level not in LoggingSeverity.__members__.values():
                results.append(result_msg(successful=False, reason=_INVALID))
                continue
            set_logger_level(level.name, level.level)
            results.append(result_msg(successful=True))
        response.results = results
        return response

    def destroy(self) -> None:
        """Withdraw both services."""
        services, self._services = self._services, None
        if services is not None:
            get_levels, set_levels = services
            self._node.destroy_service(get_levels)
            self._node.destroy_service(set_levels)
