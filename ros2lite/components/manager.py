"""A component container: the node that loads, lists and unloads other nodes on request.

It serves rclcpp's container interface (`~/_container/load_node`, `unload_node`,
`list_nodes` with composition_interfaces), so `ros2 component` and launch's
`LoadComposableNodes` drive it exactly as they drive `rclcpp_components`' containers. Loaded
nodes join the container's executor; ids count up from 1 and are never reused.

A request only *selects* among registered components (:mod:`ros2lite.components.registry`):
nothing named on the wire is imported unless some installed package registered it.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ros2lite.components.registry import ComponentLoadError, find_component, load_class
from ros2lite.node import Node
from ros2lite.parameter import Parameter

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.msgs.composition_interfaces import srv
    from ros2lite.node_options import NodeOptions
    from ros2lite.parameter import Parameter

__all__ = ['ComponentManager', 'LoadedComponent']

# rcl_interfaces/msg/Log levels a LoadNode request may ask for (0: leave as it is)
LOG_LEVELS = {10, 20, 30, 40, 50}


def _srv(name: str) -> Any:  # the composition_interfaces service class `name`
    from ros2lite.interfaces import get_interface

    return get_interface(f'composition_interfaces/srv/{name}')


@dataclass
class LoadedComponent:
    """A node the container made, and from what."""

    unique_id: int
    plugin: str
    node: Node


class ComponentManager(Node):
    """The container node (named `ComponentManager`, as rclcpp's). Add it to an executor
    before loading anything: components join the executor the manager is on."""

    def __init__(self, node_name: str = 'ComponentManager', **kwargs: Unpack[NodeOptions]) -> None:
        super().__init__(node_name, **kwargs)
        self.components: dict[int, LoadedComponent] = {}
        self._next_id = 1
        self.create_service(_srv('LoadNode'), '~/_container/load_node', self._on_load_node)
        self.create_service(_srv('UnloadNode'), '~/_container/unload_node', self._on_unload_node)
        self.create_service(_srv('ListNodes'), '~/_container/list_nodes', self._on_list_nodes)

    # -- the library side -----------------------------------------------------------------------
    def load(
        self,
        package: str,
        plugin: str,
        *,
        node_name: str = '',
        node_namespace: str = '',
        log_level: int = 0,
        remap_rules: list[str] | None = None,
        parameters: list[Parameter] | None = None,
        extra_arguments: list[Parameter] | None = None,
    ) -> LoadedComponent:
        """Build the component and add it to the executor; ComponentLoadError (with the
        reason a client sees) when it cannot be. `parameters` and `extra_arguments` are
        :class:`ros2lite.parameter.Parameter` objects."""
        if log_level and log_level not in LOG_LEVELS:
            raise ComponentLoadError(f'Invalid log level {log_level}')
        use_global = self._global_arguments(extra_arguments or [])
        component = find_component(package, plugin)
        self.get_logger().info(f'Load component: {plugin} ({component.target})')
        cls = load_class(component)
        cli_args = ['--ros-args']
        if node_name:
            cli_args += ['-r', f'__node:={node_name}']
        if node_namespace:
            cli_args += ['-r', f'__ns:={node_namespace}']
        for rule in remap_rules or []:
            cli_args += ['-r', rule]
        kwargs: dict[str, Any] = {
            'context': self.context,
            'cli_args': cli_args,
            'parameter_overrides': list(parameters or []),
            'use_global_arguments': use_global,
        }
        made: Node | None = None
        try:
            if isinstance(cls, type) and issubclass(cls, Node):
                # made first and built after: a constructor failing half way (a publisher
                # refused after the node announced itself) must leave no ghost node
                made = cls.__new__(cls)
                init: Callable[..., None] = cls.__init__
                init(made, **kwargs)
                node: object = made
            else:
                node = cls(**kwargs)
        except Exception as e:
            if made is not None:
                with contextlib.suppress(Exception):  # as much of it as was built
                    made.destroy_node()
            raise ComponentLoadError(
                f'Component constructor threw an exception: {type(e).__name__}: {e}'
            ) from None
        if not isinstance(node, Node):
            raise ComponentLoadError(f"'{component.target}' did not build a ros2lite Node")
        if log_level:
            node.get_logger().set_level(log_level)
        loaded = LoadedComponent(self._next_id, plugin, node)
        self._next_id += 1
        self.components[loaded.unique_id] = loaded
        if self.executor is not None:
            self.executor.add_node(node)
        return loaded

    def unload(self, unique_id: int) -> None:
        """Take the component off the executor and destroy its node."""
        loaded = self.components.pop(unique_id, None)
        if loaded is None:
            raise ComponentLoadError(f'No node found with unique_id: {unique_id}')
        if loaded.node.executor is not None:
            loaded.node.executor.remove_node(loaded.node)
        loaded.node.destroy_node()

    def unload_all(self) -> None:
        """Destroy every loaded component (the container is going away)."""
        for unique_id in list(self.components):
            self.unload(unique_id)

    def destroy_node(self) -> None:
        """Destroy the loaded components first, then the container."""
        self.unload_all()
        super().destroy_node()

    @staticmethod
    def _global_arguments(extra_arguments: list[Parameter]) -> bool:
        """rclcpp's extra arguments: `use_intra_process_comms` (accepted; ros2lite has no
        intra-process shortcut, so it changes nothing) and `forward_global_arguments`."""
        forward = False
        for arg in extra_arguments:
            if arg.name in ('use_intra_process_comms', 'forward_global_arguments'):
                if not isinstance(arg.value, bool):
                    raise ComponentLoadError(
                        f"Extra component argument '{arg.name}' must be a boolean"
                    )
                if arg.name == 'forward_global_arguments':
                    forward = arg.value
        return forward

    # -- the services ---------------------------------------------------------------------------
    def _on_load_node(
        self, request: srv.LoadNode.Request, response: srv.LoadNode.Response
    ) -> srv.LoadNode.Response:

        try:
            parameters = [Parameter.from_parameter_msg(p) for p in request.parameters]
            extra = [Parameter.from_parameter_msg(p) for p in request.extra_arguments]
            loaded = self.load(
                request.package_name,
                request.plugin_name,
                node_name=request.node_name,
                node_namespace=request.node_namespace,
                log_level=request.log_level,
                remap_rules=list(request.remap_rules),
                parameters=parameters,
                extra_arguments=extra,
            )
        except Exception as e:  # whatever the request or the component did: answer, go on
            self.get_logger().error(f'Failed to load component: {e}')
            response.success = False
            response.error_message = str(e)
            return response
        response.success = True
        response.full_node_name = loaded.node.get_fully_qualified_name()
        response.unique_id = loaded.unique_id
        return response

    def _on_unload_node(
        self, request: srv.UnloadNode.Request, response: srv.UnloadNode.Response
    ) -> srv.UnloadNode.Response:
        try:
            self.unload(request.unique_id)
        except ComponentLoadError as e:
            self.get_logger().warn(str(e))
            response.success = False
            response.error_message = str(e)
            return response
        response.success = True
        return response

    def _on_list_nodes(
        self, request: srv.ListNodes.Request, response: srv.ListNodes.Response
    ) -> srv.ListNodes.Response:
        response.unique_ids = list(self.components)
        response.full_node_names = [
            c.node.get_fully_qualified_name() for c in self.components.values()
        ]
        return response
