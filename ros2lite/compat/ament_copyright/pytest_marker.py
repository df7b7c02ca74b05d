"""The `copyright` pytest marker the generated test carries (a pytest plugin, as ROS's is)."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import pytest


def pytest_configure(config: pytest.Config) -> None:
    """Register the marker, so `-m copyright` selects the test and pytest does not warn."""
    config.addinivalue_line('markers', 'copyright: marks tests checking for copyright notices')
