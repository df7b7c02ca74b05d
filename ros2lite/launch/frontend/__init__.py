"""XML and YAML launch files: both are read into :class:`~.entity.Entity` trees, and one set
of builders (:mod:`.builders`) turns those into the same actions a Python launch file makes."""

from __future__ import annotations

from .loader import load_frontend_file

__all__ = ['load_frontend_file']
