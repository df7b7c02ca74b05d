"""The parameter half of `Node`'s API (rclpy's method names), kept out of node.py.

`Node` inherits `ParameterMixin` and calls `_init_parameters` once its name, clock and
publishers work. The rules live in `ParameterStore`; this class wires the store to the node:
overrides from `--ros-args`, /parameter_events, the parameter services and `use_sim_time`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, cast

from ros2lite.parameter import AllowableParameterValue, Parameter
from ros2lite.parameters.events import ParameterEventPublisher
from ros2lite.parameters.files import ParamsFileError, values_for_node
from ros2lite.parameters.services import ParameterService
from ros2lite.parameters.store import (
    OnSetCallback,
    ParameterDeclaration,
    ParameterStore,
    PostSetCallback,
    PreSetCallback,
    SharedParameterMethods,
    descriptor,
)
from ros2lite.runtime.arguments import RosArgs, RosArgsError

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces.msg import (
        ListParametersResult,
        ParameterDescriptor,
        ParameterValue,
        SetParametersResult,
    )
    from ros2lite.node_interface import NodeInterface


class ParameterMixin(SharedParameterMethods):
    """Parameters of a node: declare, get, set, describe, callbacks (as rclpy.node.Node)."""

    _parameter_store: ParameterStore

    def _init_parameters(
        self,
        ros_args: RosArgs,
        parameter_overrides: Sequence[Parameter] | None,
        allow_undeclared_parameters: bool,
        automatically_declare_parameters_from_overrides: bool,
        start_parameter_services: bool = True,
    ) -> None:

        node = cast('NodeInterface', self)  # the mixin of Node
        overrides = _override_parameters(
            node_overrides(ros_args, node.get_fully_qualified_name(), node.get_name())
        )
        overrides.update({p.name: p for p in parameter_overrides or []})
        self._parameter_store = ParameterStore(
            overrides=overrides,
            allow_undeclared=allow_undeclared_parameters,
            emit=ParameterEventPublisher(node),
        )
        if automatically_declare_parameters_from_overrides:
            self.declare_parameters(
                "",
                [(name, p.value, _descriptor()) for name, p in overrides.items()],
                ignore_override=True,
            )
        if start_parameter_services:
            self._start_parameter_services()

    def _start_parameter_services(self) -> None:

        self._parameter_service = ParameterService(cast('NodeInterface', self))

    # -- declare -----------------------------------------------------------------------------
    def declare_parameter(
        self,
        name: str,
        value: AllowableParameterValue | Parameter.Type | ParameterValue = None,
        descriptor: ParameterDescriptor | None = None,
        ignore_override: bool = False,
    ) -> Parameter:
        """Declare one parameter; returns it with its effective value (an override wins)."""
        entry: ParameterDeclaration = (
            (name,)
            if value is None and descriptor is None
            else (name, value, descriptor if descriptor is not None else _descriptor())
        )
        return self._parameter_store.declare_parameters("", [entry], ignore_override)[0]

    def undeclare_parameter(self, name: str) -> None:
        """Forget a (not read-only) parameter."""
        self._parameter_store.undeclare_parameter(name)

    # -- read --------------------------------------------------------------------------------
    def has_parameter(self, name: str) -> bool:
        """Whether `name` is declared."""
        return self._parameter_store.has_parameter(name)

    def get_parameter(self, name: str) -> Parameter:
        """A declared parameter (ParameterNotDeclaredException otherwise)."""
        return self._parameter_store.get_parameter(name)

    def get_parameters(self, names: list[str]) -> list[Parameter]:
        """get_parameter() of each name."""
        return self._parameter_store.get_parameters(names)

    def get_parameter_or(self, name: str, alternative_value: Parameter | None = None) -> Parameter:
        """The parameter, or `alternative_value` when undeclared or not set."""
        return self._parameter_store.get_parameter_or(name, alternative_value)

    def get_parameters_by_prefix(self, prefix: str) -> dict[str, Parameter]:
        """Parameters under `prefix.`, by their names relative to it."""
        return self._parameter_store.get_parameters_by_prefix(prefix)

    def get_parameter_type(self, name: str) -> Parameter.Type:
        """A parameter's type."""
        return self._parameter_store.get_parameter_type(name)

    def get_parameter_types(self, names: list[str]) -> list[Parameter.Type]:
        """get_parameter_type() of each name."""
        if not all(isinstance(n, str) for n in names):
            raise TypeError("All names must be instances of type str")
        return [self._parameter_store.get_parameter_type(n) for n in names]

    def describe_parameter(self, name: str) -> ParameterDescriptor:
        """A parameter's descriptor (constraints, read-only, dynamic typing)."""
        return self._parameter_store.describe_parameter(name)

    def describe_parameters(self, names: list[str]) -> list[ParameterDescriptor]:
        """describe_parameter() of each name."""
        return [self._parameter_store.describe_parameter(n) for n in names]

    def list_parameters(self, prefixes: list[str], depth: int) -> ListParametersResult:
        """Declared names (and prefixes) under `prefixes`, `depth` levels deep (0: all)."""
        return self._parameter_store.list_parameters(prefixes, depth)

    # -- write -------------------------------------------------------------------------------
    def set_parameters(self, parameter_list: Sequence[Parameter]) -> list[SetParametersResult]:
        """One SetParametersResult per parameter, each set on its own."""
        return self._parameter_store.set_parameters(parameter_list)

    def set_parameters_atomically(self, parameter_list: Sequence[Parameter]) -> SetParametersResult:
        """Set all of them or none; one result."""
        return self._parameter_store.set_parameters_atomically(parameter_list)

    def set_descriptor(
        self,
        name: str,
        descriptor: ParameterDescriptor,
        alternative_value: ParameterValue | None = None,
    ) -> ParameterValue:
        """Replace a descriptor (keeping the value if it fits, else `alternative_value`)."""
        return self._parameter_store.set_descriptor(name, descriptor, alternative_value)

    # -- callbacks ---------------------------------------------------------------------------
    # rclpy's names for the registered callbacks, newest first (read-only views)
    @property
    def _pre_set_parameters_callbacks(self) -> list[PreSetCallback]:
        return list(self._parameter_store.pre_set_callbacks)

    @property
    def _on_set_parameters_callbacks(self) -> list[OnSetCallback]:
        return list(self._parameter_store.on_set_callbacks)

    @property
    def _post_set_parameters_callbacks(self) -> list[PostSetCallback]:
        return list(self._parameter_store.post_set_callbacks)

    def _own_store(self) -> ParameterStore:
        return self._parameter_store


def _descriptor() -> ParameterDescriptor:

    return descriptor()


def _override_parameters(values: Mapping[str, object]) -> dict[str, Parameter]:
    """`-p`/params-file values as Parameters; a value no parameter type can hold is an error."""
    out: dict[str, Parameter] = {}
    for name, value in values.items():
        try:
            # Parameter() checks that the value is one a parameter can hold
            out[name] = Parameter(name, value=cast('AllowableParameterValue', value))
        except (TypeError, ValueError) as e:
            raise RosArgsError(f"Invalid value for parameter override '{name}': {e}") from None
    return out


def node_overrides(ros_args: RosArgs, node_fqn: str, node_name: str) -> dict[str, object]:
    """Values for one node from -p rules and params files, in the order they were given
    (global arguments before the node's own): a later one wins, as in rcl."""
    values: dict[str, object] = {}
    for source in ros_args.param_sources:
        if isinstance(source, Path):
            values.update(load_params_file(source, node_fqn, node_name))
        else:
            node, name, value = source
            if node in (None, node_name):
                values[name] = value
    return values


def load_params_file(path: Path, node_fqn: str, node_name: str | None = None) -> dict[str, object]:
    """Parameters for one node from a ROS 2 YAML params file (rules: parameters/files.py)."""
    try:
        return values_for_node(path, node_fqn)
    except ParamsFileError as e:
        raise RosArgsError(str(e)) from None
