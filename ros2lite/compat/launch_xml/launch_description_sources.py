"""`launch_xml.launch_description_sources`: including an XML launch file."""

from ros2lite.launch.sources import XMLLaunchDescriptionSource

__all__ = ['XMLLaunchDescriptionSource']
