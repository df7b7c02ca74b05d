"""rclpy.time's name: `Time` (defined with the clocks in :mod:`ros2lite.clock`)."""

from __future__ import annotations

from ros2lite.clock import Time

__all__ = ['Time']
