"""`msg list`: deprecated; see :mod:`ros2lite.cli.deprecated_interfaces`."""

from __future__ import annotations

from ..deprecated_interfaces import list_verb

cli = list_verb('msg')
