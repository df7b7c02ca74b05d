"""The parameter rules without a network: typing, descriptors, ranges, read-only, callbacks,
atomic vs one-by-one sets, the undeclared policy, overrides and the change reports."""

from __future__ import annotations

from typing import Any

import pytest

from ros2lite.exceptions import (
    InvalidParameterException,
    InvalidParameterTypeException,
    InvalidParameterValueException,
    ParameterAlreadyDeclaredException,
    ParameterImmutableException,
    ParameterNotDeclaredException,
    ParameterUninitializedException,
)
from ros2lite.msgs.rcl_interfaces.msg import (
    FloatingPointRange,
    IntegerRange,
    ParameterDescriptor,
    SetParametersResult,
)
from ros2lite.parameter import Parameter
from ros2lite.parameters.store import ParameterStore

T = Parameter.Type


class Events:
    def __init__(self) -> None:
        self.log: list[tuple[list[str], list[str], list[str]]] = []

    def __call__(
        self, new: list[Parameter], changed: list[Parameter], deleted: list[Parameter]
    ) -> None:
        self.log.append(
            ([p.name for p in new], [p.name for p in changed], [p.name for p in deleted])
        )


@pytest.fixture
def events() -> Events:
    return Events()


@pytest.fixture
def store(events: Events) -> ParameterStore:
    return ParameterStore(emit=events)


def test_declare_infers_a_static_type(store: ParameterStore, events: Events) -> None:
    declared = store.declare_parameters("", [("rate", 1.5), ("name", "x"), ("on", True)])
    assert [(p.name, p.type_, p.value) for p in declared] == [
        ("rate", T.DOUBLE, 1.5),
        ("name", T.STRING, "x"),
        ("on", T.BOOL, True),
    ]
    assert events.log == [(["rate"], [], []), (["name"], [], []), (["on"], [], [])]
    assert store.describe_parameter("rate").type == T.DOUBLE.value
    # static typing: another type is refused with rclpy's reason
    outcome = store.set_parameters([Parameter("rate", value=3)])[0]
    assert not outcome.successful
    assert outcome.reason == "Wrong parameter type, expected 'Type.DOUBLE' got 'Type.INTEGER'"
    assert store.get_parameter("rate").value == 1.5
    assert store.set_parameters([Parameter("rate", value=2.0)])[0].successful
    assert events.log[-1] == ([], ["rate"], [])


def test_declare_errors(store: ParameterStore) -> None:
    store.declare_parameters("ns", [("a", 1)])
    assert store.has_parameter("ns.a")
    with pytest.raises(
        ParameterAlreadyDeclaredException, match=r"Parameter\(s\) already declared: \['ns.a'\]"
    ):
        store.declare_parameters("", [("ns.a", 2)])
    with pytest.raises(InvalidParameterException):
        store.declare_parameters("", [("", 1)])
    with pytest.raises(ValueError, match="NOT_SET"):
        store.declare_parameters("", [("n", None, ParameterDescriptor())])
    with pytest.raises(TypeError, match="not a list of one of the allowed types"):
        store.declare_parameters("", [("mixed", [1, "a"])])


def test_dynamic_typing_and_type_only_declaration(store: ParameterStore) -> None:
    store.declare_parameters(
        "", [("any", 1, ParameterDescriptor(dynamic_typing=True)), ("later", T.INTEGER)]
    )
    assert store.set_parameters([Parameter("any", value="now a string")])[0].successful
    assert store.describe_parameter("any").type == T.STRING.value
    # typed but without a value: reading it is an error until it gets one
    with pytest.raises(ParameterUninitializedException):
        store.get_parameter("later")
    assert store.get_parameter_or("later", Parameter("later", value=9)).value == 9
    assert store.set_parameters([Parameter("later", value=4)])[0].successful
    assert store.get_parameter("later").value == 4


def test_override_of_the_wrong_type_fails_declaration() -> None:
    store = ParameterStore(overrides={"rate": Parameter("rate", value=2)})
    with pytest.raises(
        InvalidParameterTypeException,
        match="Trying to set parameter 'rate' to '2' of type 'INTEGER', expecting type 'DOUBLE'",
    ):
        store.declare_parameters("", [("rate", 1.0)])
    store.declare_parameters("", [("rate", 1)])
    assert store.get_parameter("rate").value == 2
    # ignore_override keeps the default
    other = ParameterStore(overrides={"x": Parameter("x", value=5)})
    assert other.declare_parameters("", [("x", 1)], ignore_override=True)[0].value == 1


def test_read_only(store: ParameterStore) -> None:
    store.declare_parameters("", [("fixed", 3, ParameterDescriptor(read_only=True))])
    outcome = store.set_parameters([Parameter("fixed", value=4)])[0]
    assert (outcome.successful, outcome.reason) == (
        False,
        "Trying to set a read-only parameter: fixed.",
    )
    with pytest.raises(
        ParameterImmutableException, match="Attempted to modify read-only parameter: fixed"
    ):
        store.undeclare_parameter("fixed")


def test_integer_range(store: ParameterStore) -> None:
    desc = ParameterDescriptor(integer_range=[IntegerRange(from_value=0, to_value=10, step=2)])
    store.declare_parameters("", [("even", 4, desc)])
    results = store.set_parameters([Parameter("even", value=v) for v in (10, 0, 12, 3, 6)])
    assert [r.successful for r in results] == [True, True, False, False, True]
    assert results[2].reason == "Parameter even out of range. Min: 0, Max: 10, value: 12"
    assert results[3].reason == (
        "The parameter value for even is not a valid step. Min: 0, max: 10, value: 3, step: 2"
    )
    with pytest.raises(InvalidParameterValueException, match="out of range"):
        store.declare_parameters("", [("bad", 11, desc)])


def test_double_range(store: ParameterStore) -> None:
    desc = ParameterDescriptor(
        floating_point_range=[FloatingPointRange(from_value=0.0, to_value=1.0, step=0.25)]
    )
    store.declare_parameters("", [("gain", 0.5, desc)])
    results = store.set_parameters(
        [Parameter("gain", value=v) for v in (1.0000000001, 0.75, 0.3, 1.5)]
    )
    assert [r.successful for r in results] == [True, True, False, False]
    assert results[2].reason.startswith("The parameter value for gain is not close enough")
    assert results[3].reason == "Parameter gain out of range Min: 0.0, Max: 1.0, value: 1.5"


def test_on_set_callback_rejects_and_order(store: ParameterStore, events: Events) -> None:
    store.declare_parameters("", [("a", 1), ("b", 2)])
    seen: list[str] = []

    def only_positive(params: list[Parameter]) -> Any:
        seen.append("first-added")
        bad = [p.name for p in params if p.value < 0]
        return SetParametersResult(successful=not bad, reason=f"negative: {bad}" if bad else "")

    def second(params: list[Parameter]) -> Any:
        seen.append("last-added")
        return SetParametersResult(successful=True)

    store.add_on_set_parameters_callback(only_positive)
    store.add_on_set_parameters_callback(second)
    events.log.clear()
    # atomic: all or nothing, one callback round, one event
    outcome = store.set_parameters_atomically([Parameter("a", value=5), Parameter("b", value=-1)])
    assert (outcome.successful, outcome.reason) == (False, "negative: ['b']")
    assert (store.get_parameter("a").value, store.get_parameter("b").value) == (1, 2)
    assert seen == ["last-added", "first-added"]  # newest first, as rclpy
    assert events.log == []
    # one by one: the good one goes through
    results = store.set_parameters([Parameter("a", value=5), Parameter("b", value=-1)])
    assert [r.successful for r in results] == [True, False]
    assert store.get_parameter("a").value == 5
    assert events.log == [([], ["a"], [])]
    store.remove_on_set_parameters_callback(only_positive)
    assert store.set_parameters([Parameter("b", value=-1)])[0].successful
    with pytest.raises(ValueError):
        store.remove_on_set_parameters_callback(only_positive)


def test_pre_and_post_set_callbacks(store: ParameterStore) -> None:
    store.declare_parameters("", [("x", 1), ("twice_x", 2)])
    after: list[list[str]] = []
    store.add_pre_set_parameters_callback(
        lambda ps: [*ps, *(Parameter("twice_x", value=p.value * 2) for p in ps if p.name == "x")]
    )
    store.add_post_set_parameters_callback(lambda ps: after.append([p.name for p in ps]))
    assert store.set_parameters([Parameter("x", value=7)])[0].successful
    assert store.get_parameter("twice_x").value == 14
    assert after == [["x", "twice_x"]]
    dropper = ParameterStore()
    dropper.declare_parameters("", [("x", 1)])
    dropper.add_pre_set_parameters_callback(lambda ps: [])
    outcome = dropper.set_parameters([Parameter("x", value=2)])[0]
    assert not outcome.successful and outcome.reason.startswith("parameter list cannot be empty")


def test_undeclared_policy(events: Events) -> None:
    strict = ParameterStore()
    with pytest.raises(
        ParameterNotDeclaredException,
        match=r"Invalid access to undeclared parameter\(s\): \['nope'\]",
    ):
        strict.set_parameters_atomically([Parameter("nope", value=1)])
    with pytest.raises(ParameterNotDeclaredException):
        strict.describe_parameter("nope")
    with pytest.raises(ParameterNotDeclaredException):
        strict.get_parameter_type("nope")
    loose = ParameterStore(allow_undeclared=True, emit=events)
    assert loose.get_parameter("nope").type_ == T.NOT_SET
    assert loose.describe_parameter("nope").type == 0
    assert loose.set_parameters([Parameter("nope", value=1)])[0].successful
    # implicitly declared parameters are dynamically typed
    assert loose.set_parameters([Parameter("nope", value="s")])[0].successful
    assert loose.describe_parameter("nope").dynamic_typing
    assert events.log == [(["nope"], [], []), ([], ["nope"], [])]


def test_deleting_by_setting_not_set(events: Events) -> None:
    store = ParameterStore(emit=events)
    store.declare_parameters(
        "", [("static", 1), ("dyn", 1, ParameterDescriptor(dynamic_typing=True))]
    )
    outcome = store.set_parameters([Parameter("static")])[0]
    assert (outcome.successful, outcome.reason) == (False, "Static parameter cannot be undeclared")
    assert store.set_parameters([Parameter("dyn")])[0].successful
    assert not store.has_parameter("dyn")
    assert events.log[-1] == ([], [], ["dyn"])
    store.undeclare_parameter("static")
    assert events.log[-1] == ([], [], ["static"])
    with pytest.raises(ParameterNotDeclaredException):
        store.undeclare_parameter("static")


def test_list_parameters_prefixes_and_depth(store: ParameterStore) -> None:
    store.declare_parameters("", [("a", 1), ("b.c", 1), ("b.d.e", 1), ("bb", 1)])
    everything = store.list_parameters([], 0)
    assert (everything.names, everything.prefixes) == (["a", "b.c", "b.d.e", "bb"], ["b", "b.d"])
    assert store.list_parameters([], 1).names == ["a", "bb"]
    assert store.list_parameters(["b"], 0).names == ["b.c", "b.d.e"]
    assert store.list_parameters(["b"], 1).names == ["b.c"]
    with pytest.raises(ValueError):
        store.list_parameters([], -1)


def test_getters(store: ParameterStore) -> None:
    store.declare_parameters("", [("motor.left", 1), ("motor.right", 2), ("other", "x")])
    assert {k: p.value for k, p in store.get_parameters_by_prefix("motor").items()} == {
        "left": 1,
        "right": 2,
    }
    assert [p.value for p in store.get_parameters(["other", "motor.left"])] == ["x", 1]
    assert store.get_parameter_type("other") == T.STRING
    assert store.get_parameter_or("missing").type_ == T.NOT_SET


def test_set_descriptor(store: ParameterStore) -> None:
    from ros2lite.msgs.rcl_interfaces.msg import ParameterValue

    store.declare_parameters("", [("speed", 50)])
    limited = ParameterDescriptor(
        type=T.INTEGER.value, integer_range=[IntegerRange(from_value=0, to_value=10, step=0)]
    )
    value = store.set_descriptor("speed", limited, ParameterValue(type=2, integer_value=10))
    assert value.integer_value == 10 and store.get_parameter("speed").value == 10
    with pytest.raises(InvalidParameterValueException):
        store.set_descriptor(
            "speed",
            ParameterDescriptor(
                type=T.INTEGER.value,
                integer_range=[IntegerRange(from_value=20, to_value=30, step=0)],
            ),
        )
