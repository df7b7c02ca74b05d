"""Generated classes behave like rclpy's: defaults, validation, repr, equality."""

from __future__ import annotations

from array import array

import pytest

from ros2lite.interfaces import FieldError, get_interface


def test_keyword_constructor_defaults_and_repr() -> None:
    twist = get_interface('geometry_msgs/msg/Twist')()
    assert repr(twist) == (
        'geometry_msgs.msg.Twist(linear=geometry_msgs.msg.Vector3(x=0.0, y=0.0, z=0.0), '
        'angular=geometry_msgs.msg.Vector3(x=0.0, y=0.0, z=0.0))'
    )
    assert get_interface('geometry_msgs/msg/Quaternion')().w == 1.0
    with pytest.raises(TypeError):
        get_interface('std_msgs/msg/String')(nope=1)


def test_constants_and_field_types() -> None:
    status = get_interface('action_msgs/msg/GoalStatus')
    assert status.STATUS_SUCCEEDED == 4
    assert (
        get_interface('sensor_msgs/msg/LaserScan').get_fields_and_field_types()['ranges']
        == 'sequence<float>'
    )
    fields = get_interface('sensor_msgs/msg/Imu').get_fields_and_field_types()
    assert fields['orientation_covariance'] == 'double[9]'
    assert fields['header'] == 'std_msgs/Header'


@pytest.mark.parametrize(
    ('type_name', 'field', 'value', 'message'),
    [
        ('std_msgs/msg/Int8', 'data', 128, "The 'data' field must be an integer in [-128, 127]"),
        ('std_msgs/msg/Int8', 'data', 'x', "The 'data' field must be of type 'int'"),
        ('std_msgs/msg/String', 'data', 5, "The 'data' field must be of type 'str'"),
        ('std_msgs/msg/Bool', 'data', 1, "The 'data' field must be of type 'bool'"),
        ('std_msgs/msg/Float32', 'data', 1e39, "The 'data' field must be a float in"),
        ('sensor_msgs/msg/Imu', 'orientation_covariance', [0.0], 'exactly 9 elements'),
        ('geometry_msgs/msg/Twist', 'linear', 3, "must be a sub message of type"),
        (
            'type_description_interfaces/msg/FieldType',
            'nested_type_name',
            'x' * 300,
            'not longer than',
        ),
    ],
)
def test_validation_on_assignment(type_name: str, field: str, value: object, message: str) -> None:
    msg = get_interface(type_name)()
    with pytest.raises(FieldError) as err:
        setattr(msg, field, value)
    assert message in str(err.value)


def test_sequences_become_arrays_and_ints_widen_to_float() -> None:
    scan = get_interface('sensor_msgs/msg/LaserScan')(ranges=[1, 2.5])
    assert isinstance(scan.ranges, array) and scan.ranges.typecode == 'f'
    assert list(scan.ranges) == [1.0, 2.5]
    vec = get_interface('geometry_msgs/msg/Vector3')(x=1)
    assert vec.x == 1.0 and isinstance(vec.x, float)
    with pytest.raises(FieldError):
        get_interface('std_msgs/msg/UInt8MultiArray')(data=[256])


def test_equality() -> None:
    point = get_interface('geometry_msgs/msg/Point')
    assert point(x=1.0) == point(x=1.0)
    assert point(x=1.0) != point(x=2.0)
    assert point() != get_interface('geometry_msgs/msg/Vector3')()


def test_service_and_action_namespaces() -> None:
    srv = get_interface('example_interfaces/srv/AddTwoInts')
    assert srv.Request().a == 0 and srv.Response().sum == 0
    assert srv.Event().info.event_type == 0
    with pytest.raises(NotImplementedError):
        srv()
    act = get_interface('example_interfaces/action/Fibonacci')
    assert act.SendGoal.Request().goal == act.Goal()
    assert act.GetResult.Response().result == act.Result()
    assert act.FeedbackMessage().feedback == act.Feedback()
    assert (
        get_interface('example_interfaces/action/Fibonacci_SendGoal_Request')
        is act.SendGoal.Request
    )


def test_field_checks_can_be_off_as_in_jazzy(monkeypatch: pytest.MonkeyPatch) -> None:
    """ROS_PYTHON_CHECK_FIELDS=0 (a ROS shell's default): assignments are not checked,
    sequences still take their stored form; filling from outside input always checks."""
    from ros2lite.interfaces import set_message_fields
    from ros2lite.interfaces.classes import _CHECK

    monkeypatch.setattr(_CHECK, 'on', False)
    event_type = get_interface('rcl_interfaces/msg/ParameterEvent')
    stand_in = object()
    assert event_type(new_parameters=[stand_in]).new_parameters == [stand_in]
    floats = get_interface('std_msgs/msg/Float64MultiArray')(data=[1, 2])
    assert floats.data.typecode == 'd' and list(floats.data) == [1.0, 2.0]
    from ros2lite.interfaces.errors import PopulateError

    with pytest.raises(PopulateError, match='at most 1 elements'):  # checked all the same
        set_message_fields(get_interface('std_srvs/srv/SetBool_Event')(), {'request': [{}, {}]})
    monkeypatch.setattr(_CHECK, 'on', True)
    with pytest.raises(FieldError):
        event_type(new_parameters=[stand_in])


@pytest.mark.parametrize('checks', [True, False])
def test_byte_constants_are_bytes_and_fill_byte_fields(
    monkeypatch: pytest.MonkeyPatch, checks: bool
) -> None:
    """As rosidl's Python classes: a `byte` constant is one-byte `bytes`, so
    `DiagnosticStatus(level=DiagnosticStatus.WARN)` serializes whether or not assignments
    are checked; `byte` fields default to b'\\x00', `char` ones are uint8 ints."""
    from ros2lite.interfaces import deserialize, serialize
    from ros2lite.interfaces.classes import _CHECK

    monkeypatch.setattr(_CHECK, 'on', checks)
    status = get_interface('diagnostic_msgs/msg/DiagnosticStatus')
    assert (status.OK, status.WARN, status.ERROR, status.STALE) == (
        b'\x00',
        b'\x01',
        b'\x02',
        b'\x03',
    )
    warn = status(level=status.WARN, name='n')
    assert deserialize(status, serialize(warn)).level == status.WARN
    assert status().level == b'\x00'
    assert get_interface('std_msgs/msg/Char')().data == 0
    assert get_interface('std_msgs/msg/Byte')().data == b'\x00'
