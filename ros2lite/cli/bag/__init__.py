"""`ros2lite bag`: record, play and inspect rosbag2 bags (MCAP, and sqlite3 for reading)."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    "burst": (__name__ + ".burst", "Burst data from a bag"),
    "convert": (
        __name__ + ".convert",
        "Given an input bag, write out a new bag with different settings",
    ),
    "info": (__name__ + ".info", "Print information about a bag to the screen"),
    "list": (__name__ + ".list", "Print information about available plugins to the screen"),
    "play": (__name__ + ".play", "Play back ROS data from a bag"),
    "record": (__name__ + ".record", "Record ROS data to a bag"),
    "reindex": (__name__ + ".reindex", "Reconstruct metadata file for a bag"),
}

cli = command_group("bag", "Various rosbag related sub-commands", VERBS)
