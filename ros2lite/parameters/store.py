"""One node's parameters: declaration, descriptors, validation, callbacks and change events.

Behaviour follows rclpy's Node (Jazzy): static typing unless the descriptor asks for dynamic
typing, read-only and range constraints, pre-set / on-set / post-set callbacks, the
undeclared-parameter policy, and one change event per successful declare, set or undeclare.
The store knows nothing about the network: `emit` receives (new, changed, deleted) lists and
the node turns them into /parameter_events messages.
"""

from __future__ import annotations

import copy
import math
import threading
import warnings
from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, TypeGuard, cast

from ros2lite.exceptions import (
    InvalidParameterException,
    InvalidParameterTypeException,
    InvalidParameterValueException,
    ParameterAlreadyDeclaredException,
    ParameterImmutableException,
    ParameterNotDeclaredException,
    ParameterUninitializedException,
)
from ros2lite.parameter import (
    PARAMETER_SEPARATOR_STRING,
    AllowableParameterValue,
    Parameter,
    parameter_value_to_python,
)

if TYPE_CHECKING:
    from ros2lite.msgs.rcl_interfaces.msg import (
        FloatingPointRange,
        IntegerRange,
        ListParametersResult,
        ParameterDescriptor,
        ParameterValue,
        SetParametersResult,
    )

EmitFn = Callable[[list[Parameter], list[Parameter], list[Parameter]], None]
PreSetCallback = Callable[[list[Parameter]], list[Parameter]]
OnSetCallback = Callable[[list[Parameter]], 'SetParametersResult']
PostSetCallback = Callable[[list[Parameter]], None]
ParameterDeclaration = (
    tuple[str]
    | tuple[str, 'AllowableParameterValue | Parameter.Type | ParameterValue']
    | tuple[str, 'AllowableParameterValue | Parameter.Type | ParameterValue', 'ParameterDescriptor']
)
"""(name[, default value or Parameter.Type[, descriptor]]), as rclpy's declare_parameters."""

DEPTH_RECURSIVE = 0  # rcl_interfaces/srv/ListParameters: every level
WRONG_TYPE = "Wrong parameter type"


def descriptor(
    name: str = "",
    type_number: int = 0,
    dynamic_typing: bool = False,
    *,
    description: str = "",
    read_only: bool = False,
) -> ParameterDescriptor:
    """A new rcl_interfaces/msg/ParameterDescriptor."""
    from ros2lite.interfaces import get_interface

    cls: type[ParameterDescriptor] = get_interface("rcl_interfaces/msg/ParameterDescriptor")
    return cls(
        name=name,
        type=type_number,
        dynamic_typing=dynamic_typing,
        description=description,
        read_only=read_only,
    )


def result(successful: bool, reason: str = "") -> SetParametersResult:
    """A new rcl_interfaces/msg/SetParametersResult."""
    from ros2lite.interfaces import get_interface

    cls: type[SetParametersResult] = get_interface("rcl_interfaces/msg/SetParametersResult")
    return cls(successful=successful, reason=reason)


def validate_parameter_name(name: str) -> bool:
    """A parameter name is a non-empty string without white space; True if it is (rclpy's
    answer), InvalidParameterException otherwise."""
    if not isinstance(name, str) or not name or any(c.isspace() for c in name):
        raise InvalidParameterException(name)
    return True


class SharedParameterMethods:
    """rclpy's parameter methods that read the same on a node and on its store, written
    once: the store does the work, and the node inherits these methods and hands them its
    own store. The set callbacks are kept newest first, the order they run in."""

    def _own_store(self) -> ParameterStore:
        """The store that holds the parameters and the callbacks."""
        raise NotImplementedError

    def declare_parameters(
        self,
        namespace: str,
        parameters: Sequence[ParameterDeclaration],
        ignore_override: bool = False,
    ) -> list[Parameter]:
        """Declare each (name[, value or Parameter.Type[, descriptor]]) as `namespace.name`."""
        return self._own_store().declare_all(namespace, parameters, ignore_override)

    def add_pre_set_parameters_callback(self, callback: PreSetCallback) -> None:
        """`callback(parameters)` may change the list being set, before any check."""
        self._own_store().pre_set_callbacks.insert(0, callback)

    def add_on_set_parameters_callback(self, callback: OnSetCallback) -> None:
        """`callback(parameters)` may refuse a set (an unsuccessful SetParametersResult)."""
        self._own_store().on_set_callbacks.insert(0, callback)

    def add_post_set_parameters_callback(self, callback: PostSetCallback) -> None:
        """`callback(parameters)` learns of every successful set."""
        self._own_store().post_set_callbacks.insert(0, callback)

    def remove_pre_set_parameters_callback(self, callback: PreSetCallback) -> None:
        """Forget a pre-set callback."""
        self._own_store().pre_set_callbacks.remove(callback)

    def remove_on_set_parameters_callback(self, callback: OnSetCallback) -> None:
        """Forget an on-set callback."""
        self._own_store().on_set_callbacks.remove(callback)

    def remove_post_set_parameters_callback(self, callback: PostSetCallback) -> None:
        """Forget a post-set callback."""
        self._own_store().post_set_callbacks.remove(callback)


class ParameterStore(SharedParameterMethods):
    """A node's parameters and descriptors; thread-safe (services run on executor threads)."""

    PARAM_REL_TOL = 1e-6  # how close a double must be to a range's edge or step

    def __init__(
        self,
        *,
        overrides: dict[str, Parameter] | None = None,
        allow_undeclared: bool = False,
        emit: EmitFn | None = None,
    ) -> None:
        self.overrides: dict[str, Parameter] = dict(overrides or {})
        self.allow_undeclared = allow_undeclared
        self._emit = emit
        self._parameters: dict[str, Parameter] = {}
        self._descriptors: dict[str, ParameterDescriptor] = {}
        self._pre_set: list[PreSetCallback] = []
        self._on_set: list[OnSetCallback] = []
        self._post_set: list[PostSetCallback] = []
        self._lock = threading.RLock()

    def _own_store(self) -> ParameterStore:
        return self

    @property
    def pre_set_callbacks(self) -> list[PreSetCallback]:
        """The pre-set callbacks, newest first: the list itself, which the shared methods edit."""
        return self._pre_set

    @property
    def on_set_callbacks(self) -> list[OnSetCallback]:
        """The on-set callbacks, newest first (the list itself)."""
        return self._on_set

    @property
    def post_set_callbacks(self) -> list[PostSetCallback]:
        """The post-set callbacks, newest first (the list itself)."""
        return self._post_set

    def declare_all(
        self,
        namespace: str,
        parameters: Sequence[ParameterDeclaration],
        ignore_override: bool = False,
    ) -> list[Parameter]:
        """declare_parameters' work, under the store's lock: a name already taken declares
        none of them."""
        todo: list[tuple[Parameter, ParameterDescriptor]] = []
        for index, entry in enumerate(parameters):
            todo.append(self._prepare(namespace, index, entry, ignore_override))
        with self._lock:
            taken = [p.name for p, _ in todo if p.name in self._parameters]
            if taken:
                raise ParameterAlreadyDeclaredException(taken)
            for param, desc in todo:
                outcome = self._set_atomically([param], {param.name: desc}, allow_not_set=True)
                if not outcome.successful:
                    if outcome.reason.startswith(WRONG_TYPE):
                        raise InvalidParameterTypeException(param, Parameter.Type(desc.type).name)
                    raise InvalidParameterValueException(param.name, param.value, outcome.reason)
            return [self._parameters[p.name] for p, _ in todo]

    def _prepare(
        self, namespace: str, index: int, entry: ParameterDeclaration, ignore_override: bool
    ) -> tuple[Parameter, ParameterDescriptor]:
        if not isinstance(entry, (tuple, list)) or not 1 <= len(entry) <= 3:
            raise TypeError(
                f"Invalid parameter tuple length at index {index} in parameters "
                f"list: {entry}; expecting length between 1 and 3"
            )
        name = entry[0]
        if not isinstance(name, str):
            raise TypeError(
                f"First element {name} at index {index} in parameters list is not a str."
            )
        if namespace:
            name = f"{namespace}{PARAMETER_SEPARATOR_STRING}{name}"
        validate_parameter_name(name)
        second = entry[1] if len(entry) > 1 else None
        desc = copy.deepcopy(entry[2]) if len(entry) == 3 else descriptor()
        if not hasattr(desc, "dynamic_typing"):
            raise TypeError(
                f"Third element {desc} at index {index} in parameters list is "
                "not a ParameterDescriptor."
            )
        if len(entry) == 1:
            warnings.warn(
                f"when declaring parameter named '{name}', declaring a parameter "
                "only providing its name is deprecated: give a default value, a "
                "Parameter.Type or a descriptor with dynamic_typing=True",
                UserWarning,
                stacklevel=4,
            )
            desc.dynamic_typing = True
        value: AllowableParameterValue = None
        if isinstance(second, Parameter.Type):
            if second == Parameter.Type.NOT_SET:
                raise ValueError(
                    f"Cannot declare parameter {{{name}}} as statically typed of type NOT_SET"
                )
            if desc.dynamic_typing:
                raise ValueError(
                    f"When declaring parameter {{{name}}} passing a descriptor "
                    "with `dynamic_typing=True` is not allowed when the "
                    "parameter type is provided"
                )
            desc.type = second.value
        else:
            if _is_value_msg(second):
                value = parameter_value_to_python(second)
            else:  # anything else: Parameter() below says whether it may be a value
                value = cast("AllowableParameterValue", second)
            if not desc.dynamic_typing:
                desc.type = Parameter.Type.from_parameter_value(value).value
                if desc.type == Parameter.Type.NOT_SET.value:
                    raise ValueError(
                        "Cannot declare a statically typed parameter with "
                        "default value of type PARAMETER_NOT_SET"
                    )
        if not ignore_override and name in self.overrides:
            value = self.overrides[name].value
        return Parameter(name, value=value), desc

    def undeclare_parameter(self, name: str) -> None:
        """Forget a parameter (not a read-only one); reported as deleted."""
        with self._lock:
            if name not in self._parameters:
                raise ParameterNotDeclaredException(name)
            if self._descriptors[name].read_only:
                raise ParameterImmutableException(name)
            old = self._parameters.pop(name)
            del self._descriptors[name]
        if self._emit is not None:
            self._emit([], [], [Parameter(old.name)])

    # -- reading -----------------------------------------------------------------------------
    def has_parameter(self, name: str) -> bool:
        """Whether `name` is declared."""
        return name in self._parameters

    def names(self) -> list[str]:
        """Every declared name, in declaration order."""
        return list(self._parameters)

    def get_parameter(self, name: str) -> Parameter:
        """The parameter; an undeclared name is an error unless undeclared ones are allowed."""
        param = self._parameters.get(name)
        if param is not None:
            if param.type_ != Parameter.Type.NOT_SET or self._descriptors[name].dynamic_typing:
                return param
            raise ParameterUninitializedException(name)
        if self.allow_undeclared:
            return Parameter(name, Parameter.Type.NOT_SET, None)
        raise ParameterNotDeclaredException(name)

    def get_parameters(self, names: Iterable[str]) -> list[Parameter]:
        """get_parameter() of each name."""
        names = list(names)
        if not all(isinstance(n, str) for n in names):
            raise TypeError("All names must be instances of type str")
        return [self.get_parameter(n) for n in names]

    def get_parameter_or(self, name: str, alternative_value: Parameter | None = None) -> Parameter:
        """The parameter, or `alternative_value` when it is undeclared or not set."""
        if alternative_value is None:
            alternative_value = Parameter(name, Parameter.Type.NOT_SET)
        param = self._parameters.get(name)
        if param is None or param.type_ == Parameter.Type.NOT_SET:
            return alternative_value
        return param

    def get_parameter_type(self, name: str) -> Parameter.Type:
        """The parameter's type (NOT_SET for an undeclared one, where that is allowed)."""
        param = self._parameters.get(name)
        if param is not None:
            return param.type_
        if self.allow_undeclared:
            return Parameter.Type.NOT_SET
        raise ParameterNotDeclaredException(name)

    def get_parameters_by_prefix(self, prefix: str) -> dict[str, Parameter]:
        """Parameters under `prefix.`, by their names relative to it."""
        if prefix:
            prefix += PARAMETER_SEPARATOR_STRING
        return {
            name[len(prefix) :]: p
            for name, p in self._parameters.items()
            if name.startswith(prefix)
        }

    def describe_parameter(self, name: str) -> ParameterDescriptor:
        """The parameter's descriptor (a blank one for an undeclared name, where allowed)."""
        desc = self._descriptors.get(name)
        if desc is not None:
            return desc
        if self.allow_undeclared:
            return descriptor()
        raise ParameterNotDeclaredException(name)

    def list_parameters(self, prefixes: list[str], depth: int) -> ListParametersResult:
        """Names (and their dotted prefixes) under any of `prefixes`, `depth` levels deep."""
        if not isinstance(prefixes, list) or not all(isinstance(p, str) for p in prefixes):
            raise TypeError("The prefixes argument must be a list of str")
        if not isinstance(depth, int) or isinstance(depth, bool):
            raise TypeError("The depth must be instance of type int")
        if depth < 0:
            raise ValueError("The depth must be greater than or equal to zero")
        sep = PARAMETER_SEPARATOR_STRING

        def shallow(name: str) -> bool:
            return name.count(sep) < depth

        from ros2lite.interfaces import get_interface

        result_type: type[ListParametersResult] = get_interface(
            "rcl_interfaces/msg/ListParametersResult"
        )
        out = result_type()
        for name in list(self._parameters):
            if prefixes or depth != DEPTH_RECURSIVE:
                wanted = (not prefixes and shallow(name)) or any(
                    name == p
                    or (
                        name.startswith(p + sep)
                        and (depth == DEPTH_RECURSIVE or shallow(name[len(p) + 1 :]))
                    )
                    for p in prefixes
                )
                if not wanted:
                    continue
            out.names.append(name)
            if sep in name:
                prefix = name.rsplit(sep, 1)[0]
                if prefix not in out.prefixes:
                    out.prefixes.append(prefix)
        return out

    # -- setting -----------------------------------------------------------------------------
    def set_parameters(self, parameters: Sequence[Parameter]) -> list[SetParametersResult]:
        """Set one at a time; stops (raising) at the first undeclared one if not allowed."""
        return [self.set_parameters_atomically([p]) for p in parameters]

    def set_parameters_atomically(self, parameters: Sequence[Parameter]) -> SetParametersResult:
        """All or nothing: one callback round and one event for the whole list."""
        params = list(parameters)
        with self._lock:
            if self._pre_set:
                modified: list[Parameter] = []
                for cb in self._pre_set:
                    modified.extend(cb(params))
                params = modified
                if not params:
                    return result(
                        False,
                        "parameter list cannot be empty, this might be due "
                        "to pre_set_parameters_callback modifying the original "
                        "parameters list.",
                    )
            if not all(isinstance(p, Parameter) for p in params):
                raise TypeError("parameter must be instance of type 'Parameter'")
            undeclared = [p.name for p in params if p.name not in self._parameters]
            if undeclared and not self.allow_undeclared:
                raise ParameterNotDeclaredException(undeclared)
            return self._set_atomically(params, None, allow_not_set=False)

    def _set_atomically(
        self,
        params: list[Parameter],
        descriptors: dict[str, ParameterDescriptor] | None,
        allow_not_set: bool,
    ) -> SetParametersResult:
        """Check, ask the callbacks, store, then report. Caller holds the lock."""
        new_descriptors: dict[str, ParameterDescriptor] = {}
        for param in params:
            if descriptors is not None:
                desc, check_read_only = descriptors[param.name], False
            elif param.name in self._descriptors:
                desc, check_read_only = self._descriptors[param.name], True
            else:
                continue
            desc = copy.deepcopy(desc)
            outcome = self._apply_descriptor(param, desc, check_read_only)
            if not outcome.successful:
                return outcome
            new_descriptors[param.name] = desc
        for cb in self._on_set:
            outcome = cb(params)
            if not outcome.successful:
                return outcome
        new: list[Parameter] = []
        changed: list[Parameter] = []
        deleted: list[Parameter] = []
        for param in params:
            if not allow_not_set and param.type_ == Parameter.Type.NOT_SET:
                deleted.append(param)
                self._parameters.pop(param.name, None)
                self._descriptors.pop(param.name, None)
                continue
            if param.name in new_descriptors:
                self._descriptors[param.name] = new_descriptors[param.name]
            else:  # implicitly declared (undeclared parameters allowed)
                self._descriptors[param.name] = descriptor(
                    name=param.name, type_number=param.type_.value, dynamic_typing=True
                )
            if self.get_parameter_or(param.name).type_ == Parameter.Type.NOT_SET:
                new.append(param)
            else:
                changed.append(param)
            self._parameters[param.name] = param
        if self._emit is not None:
            self._emit(new, changed, deleted)
        for post in self._post_set:
            post(params)
        return result(True)

    def _apply_descriptor(
        self, param: Parameter, desc: ParameterDescriptor, check_read_only: bool
    ) -> SetParametersResult:
        """Whether `param` satisfies `desc`; fills the descriptor's name (and dynamic type)."""
        desc.name = param.name
        if check_read_only and desc.read_only:
            return result(False, f"Trying to set a read-only parameter: {param.name}.")
        not_set = param.type_ == Parameter.Type.NOT_SET
        if desc.dynamic_typing:
            desc.type = param.type_.value
        elif param.name in self._parameters and not_set:
            return result(False, "Static parameter cannot be undeclared")
        elif not not_set and param.type_.value != desc.type:
            return result(
                False, f"{WRONG_TYPE}, expected '{Parameter.Type(desc.type)}' got '{param.type_}'"
            )
        if param.type_ == Parameter.Type.INTEGER and desc.integer_range:
            return self._check_integer_range(param, desc.integer_range[0])
        if param.type_ == Parameter.Type.DOUBLE and desc.floating_point_range:
            return self._check_double_range(param, desc.floating_point_range[0])
        return result(True)

    @staticmethod
    def _check_integer_range(param: Parameter, rng: IntegerRange) -> SetParametersResult:
        lo, hi = sorted((rng.from_value, rng.to_value))
        value = param.value
        if value in (lo, hi):
            return result(True)
        if not lo < value < hi:
            return result(
                False, f"Parameter {param.name} out of range. Min: {lo}, Max: {hi}, value: {value}"
            )
        if rng.step != 0 and (value - lo) % rng.step != 0:
            return result(
                False,
                f"The parameter value for {param.name} is not a valid step. "
                f"Min: {lo}, max: {hi}, value: {value}, step: {rng.step}",
            )
        return result(True)

    def _check_double_range(self, param: Parameter, rng: FloatingPointRange) -> SetParametersResult:
        lo, hi = sorted((rng.from_value, rng.to_value))
        value = param.value
        tol = self.PARAM_REL_TOL
        if math.isclose(value, lo, rel_tol=tol) or math.isclose(value, hi, rel_tol=tol):
            return result(True)
        if not lo < value < hi:
            return result(
                False, f"Parameter {param.name} out of range Min: {lo}, Max: {hi}, value: {value}"
            )
        if rng.step != 0.0:
            steps = round((value - lo) / rng.step)
            if not math.isclose(lo + steps * rng.step, value, rel_tol=tol):
                return result(
                    False,
                    f"The parameter value for {param.name} is not close "
                    f"enough to a valid step. Min: {lo}, max: {hi}, "
                    f"value: {value}, step: {rng.step}",
                )
        return result(True)

    def set_descriptor(
        self,
        name: str,
        desc: ParameterDescriptor,
        alternative_value: ParameterValue | None = None,
    ) -> ParameterValue:
        """Replace a parameter's descriptor, keeping its value if it still fits, else taking
        `alternative_value` (a ParameterValue); returns the resulting ParameterValue."""
        with self._lock:
            if name not in self._parameters:
                if not self.allow_undeclared:
                    raise ParameterNotDeclaredException(name)
                return self.get_parameter(name).get_parameter_value()
            if self.describe_parameter(name).read_only:
                raise ParameterImmutableException(name)
            desc = copy.deepcopy(desc)
            current = self._parameters[name]
            candidates = [current]
            if alternative_value is not None:
                candidates.append(
                    Parameter(name, value=parameter_value_to_python(alternative_value))
                )
            outcome = None
            for candidate in candidates:
                trial = copy.deepcopy(desc)
                outcome = self._apply_descriptor(candidate, trial, False)
                if outcome.successful:
                    self._parameters[name] = candidate
                    desc = trial
                    break
            else:
                assert outcome is not None
                raise InvalidParameterValueException(name, candidates[-1].value, outcome.reason)
            self._descriptors[name] = desc
            return self._parameters[name].get_parameter_value()


def _is_value_msg(value: object) -> TypeGuard[ParameterValue]:
    return hasattr(value, "type") and hasattr(value, "string_array_value")
