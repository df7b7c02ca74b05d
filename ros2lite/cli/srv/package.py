"""`srv package`: deprecated; see :mod:`ros2lite.cli.deprecated_interfaces`."""

from __future__ import annotations

from ..deprecated_interfaces import package_verb

cli = package_verb('srv')
