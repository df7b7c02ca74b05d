"""`ros2lite param`: read and change the parameters of running nodes."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    "delete": "Delete parameter",
    "describe": "Show descriptive information about declared parameters",
    "dump": "Show all of the parameters of a node in a YAML file format",
    "get": "Get parameter",
    "list": "Output a list of available parameters",
    "load": "Load parameter file for a node",
    "set": "Set parameter",
}

cli = command_group(__name__, "Various param related sub-commands.", VERBS)
