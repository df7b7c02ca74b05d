"""Bags: rosbag2-compatible MCAP bags, written and read without ROS.

    from ros2lite.bag import Reader, Writer
    with Writer('my_bag') as bag:
        bag.write('/chatter', String(data='hi'), time.time_ns())
    with Reader('my_bag') as bag:
        for topic, msg, t in bag:
            ...

`Recorder` and `Player` (ros2lite.bag.recorder / .player) are what `bag record` and
`bag play` run on a live graph.
"""

from __future__ import annotations

from ros2lite.bag.errors import BagError, MetadataError
from ros2lite.bag.metadata import BagMetadata, TopicMetadata
from ros2lite.bag.reader import Reader
from ros2lite.bag.writer import Writer

__all__ = ["BagError", "BagMetadata", "MetadataError", "Reader", "TopicMetadata", "Writer"]
