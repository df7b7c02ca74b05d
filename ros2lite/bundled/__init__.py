"""Bundled demo nodes, so a fresh install can show a working graph without a ROS install.

Each demo package mirrors the ROS one it is named after (same node names, topics, QoS and log
lines), which makes them usable as stand-ins next to real ROS 2 nodes on rmw_zenoh.
"""
