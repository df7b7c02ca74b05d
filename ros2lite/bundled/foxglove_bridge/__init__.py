"""The `foxglove_bridge` package: the live graph over the Foxglove WebSocket protocol.

The protocol itself is the `foxglove-sdk` package's (the Foxglove team's implementation);
this package only maps the ROS graph onto it: topics to channels, services, parameters,
the connection graph and time.
"""
