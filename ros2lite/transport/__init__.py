"""The rmw_zenoh wire protocol: keys, tokens, QoS chunks, attachments, session config.

This package moves bytes and names and is the only code that imports zenoh; the ROS concepts
it encodes (names, QoS profiles) and the security it applies live outside it. Only
``config``/``open`` (configs; opening sessions and routers), ``session``, ``pull``,
``security`` and ``admin`` import zenoh, so ``keys``/``qos``/``attachment``/``endpoints``
stay cheap for the CLI.
"""
