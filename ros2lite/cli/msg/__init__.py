"""`ros2lite msg`: ros2cli's deprecated message listing (use `interface`)."""

from __future__ import annotations

from ..deprecated_interfaces import verbs
from ..lazy import command_group

VERBS = verbs('msg')

cli = command_group(__name__, 'Various msg related sub-commands.', VERBS)
