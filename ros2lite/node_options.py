"""The keyword options of `Node(...)`, for code that builds nodes on another's behalf.

Subclasses and factories (`ros2lite.create_node`, component and lifecycle nodes, the demos)
take `**options: Unpack[NodeOptions]` and hand them on to :class:`ros2lite.node.Node`, so a
type checker still checks every option by name and type. It lists `Node.__init__`'s
keyword-only parameters (keep them in step).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, TypedDict

if TYPE_CHECKING:
    from ros2lite.context import Context
    from ros2lite.parameter import Parameter

__all__ = ['NodeOptions']


class NodeOptions(TypedDict, total=False):
    """`Node`'s keyword options; see :class:`ros2lite.node.Node`."""

    context: Context | None
    cli_args: list[str] | None
    namespace: str | None
    use_global_arguments: bool
    enable_rosout: bool
    parameter_overrides: list[Parameter] | None
    allow_undeclared_parameters: bool
    automatically_declare_parameters_from_overrides: bool
    start_parameter_services: bool
