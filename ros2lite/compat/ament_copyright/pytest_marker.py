"""The `copyright` pytest marker the generated test carries (a pytest plugin, as ROS's is)."""

from __future__ import annotations

from typing import Any


def pytest_configure(config: Any) -> None:
    """Register the marker, so `-m copyright` selects the test and pytest does not warn."""
    config.addinivalue_line('markers', 'copyright: marks tests checking for copyright notices')
