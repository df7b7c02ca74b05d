"""`launch.events.process`: process events under launch's names."""

from ros2lite.launch.events import (
    ProcessEvent,
    ProcessExited,
    ProcessIO,
    ProcessStarted,
    ProcessStderr,
    ProcessStdout,
    ShutdownProcess,
    SignalProcess,
)

__all__ = [
    'ProcessEvent',
    'ProcessExited',
    'ProcessIO',
    'ProcessStarted',
    'ProcessStderr',
    'ProcessStdout',
    'ShutdownProcess',
    'SignalProcess',
]
