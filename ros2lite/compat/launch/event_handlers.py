"""`launch.event_handlers`: ros2lite's event handlers under launch's names."""

from ros2lite.launch.event_handlers import (
    EventHandler,
    OnExecutionComplete,
    OnProcessExit,
    OnProcessIO,
    OnProcessStart,
    OnShutdown,
)

__all__ = [
    'EventHandler',
    'OnExecutionComplete',
    'OnProcessExit',
    'OnProcessIO',
    'OnProcessStart',
    'OnShutdown',
]
