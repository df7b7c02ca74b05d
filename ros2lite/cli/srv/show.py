"""`srv show`: deprecated; see :mod:`ros2lite.cli.deprecated_interfaces`."""

from __future__ import annotations

from ..deprecated_interfaces import show_verb

cli = show_verb('srv')
