"""tf2_ros's command-line tools: static_transform_publisher, tf2_echo, tf2_monitor."""
