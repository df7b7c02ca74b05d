"""Components: node classes loaded into a container process by name, as rclcpp_components
does it — the registry (where classes come from), the container node, and the client side
that `ros2lite component` uses."""

from __future__ import annotations

from ros2lite.components.manager import ComponentManager, LoadedComponent
from ros2lite.components.registry import ComponentLoadError, ComponentType, component_types

__all__ = [
    'ComponentLoadError',
    'ComponentManager',
    'ComponentType',
    'LoadedComponent',
    'component_types',
]
