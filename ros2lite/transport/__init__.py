"""The rmw_zenoh wire protocol: keys, tokens, QoS chunks, attachments, session config.

This package moves bytes and names and is the only code that imports zenoh; the ROS concepts
it encodes (names, QoS profiles) live outside it. Only :mod:`~ros2lite.transport.config`,
:mod:`~ros2lite.transport.session` and :mod:`~ros2lite.transport.admin` import zenoh, so
``keys``/``qos``/``attachment`` stay cheap for the CLI.
"""
