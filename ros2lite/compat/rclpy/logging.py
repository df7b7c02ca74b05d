"""rclpy.logging."""

from ros2lite.logging import (
    LoggingSeverity,
    RcutilsLogger,
    _root_logger,
    clear_config,
    get_logger,
    get_logger_effective_level,
    get_logger_level,
    get_logging_directory,
    get_logging_severity_from_string,
    set_logger_level,
)

__all__ = [
    'LoggingSeverity',
    'RcutilsLogger',
    '_root_logger',
    'clear_config',
    'get_logger',
    'get_logger_effective_level',
    'get_logger_level',
    'get_logging_directory',
    'get_logging_severity_from_string',
    'set_logger_level',
]
