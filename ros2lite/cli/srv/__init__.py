"""`ros2lite srv`: ros2cli's deprecated service listing (use `interface`)."""

from __future__ import annotations

from ..deprecated_interfaces import verbs
from ..lazy import command_group

VERBS = verbs('srv')

cli = command_group(__name__, 'Various srv related sub-commands.', VERBS)
