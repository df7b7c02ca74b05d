"""`launch.launch_description_sources`: where included launch descriptions come from."""

from ros2lite.launch.sources import (
    AnyLaunchDescriptionSource,
    FrontendLaunchDescriptionSource,
    LaunchDescriptionSource,
    PythonLaunchDescriptionSource,
)

__all__ = [
    'AnyLaunchDescriptionSource',
    'FrontendLaunchDescriptionSource',
    'LaunchDescriptionSource',
    'PythonLaunchDescriptionSource',
]
