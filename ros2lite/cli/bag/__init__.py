"""`ros2lite bag`: record, play and inspect rosbag2 bags (MCAP, and sqlite3 for reading)."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    "burst": "Burst data from a bag",
    "convert": "Given an input bag, write out a new bag with different settings",
    "cut": "Write the messages of a bag between two times into a new bag",
    "echo": "Print the messages of a bag, as topic echo prints them",
    "export": "Export one topic of a bag to CSV, JSON lines, Parquet or PNG files",
    "filter": "Write some topics of a bag into a new bag",
    "info": "Print information about a bag to the screen",
    "list": "Print information about available plugins to the screen",
    "play": "Play back ROS data from a bag",
    "plot": "Plot numeric fields of the messages in a bag",
    "record": "Record ROS data to a bag",
    "reindex": "Reconstruct metadata file for a bag",
}

cli = command_group(__name__, "Various rosbag related sub-commands", VERBS)
