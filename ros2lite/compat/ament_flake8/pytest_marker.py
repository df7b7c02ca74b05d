"""The `flake8` pytest marker the generated test carries (a pytest plugin, as ROS's is)."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import pytest


def pytest_configure(config: pytest.Config) -> None:
    """Register the marker, so `-m flake8` selects the test and pytest does not warn."""
    config.addinivalue_line('markers', 'flake8: marks tests checking for flake8 compliance')
