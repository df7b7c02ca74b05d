"""Helpers with no ROS in them: files written without following symlinks, YAML read safely,
child processes and their stop signals, single keys from a terminal."""
