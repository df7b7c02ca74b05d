"""`srv packages`: deprecated; see :mod:`ros2lite.cli.deprecated_interfaces`."""

from __future__ import annotations

from ..deprecated_interfaces import packages_verb

cli = packages_verb('srv')
