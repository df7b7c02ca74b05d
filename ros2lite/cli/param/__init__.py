"""`ros2lite param`: read and change the parameters of running nodes."""

from __future__ import annotations

from ..lazy import command_group

VERBS = {
    "delete": (__name__ + ".delete", "Delete parameter"),
    "describe": (__name__ + ".describe", "Show descriptive information about declared parameters"),
    "dump": (__name__ + ".dump", "Show all of the parameters of a node in a YAML file format"),
    "get": (__name__ + ".get", "Get parameter"),
    "list": (__name__ + ".list", "Output a list of available parameters"),
    "load": (__name__ + ".load", "Load parameter file for a node"),
    "set": (__name__ + ".set", "Set parameter"),
}

cli = command_group("param", "Various param related sub-commands.", VERBS)
