"""The .msg/.srv/.action grammar and its error messages."""

from __future__ import annotations

import pytest

from ros2lite.interfaces.errors import InterfaceError
from ros2lite.interfaces.parser import (
    Constant,
    FieldType,
    parse_action,
    parse_message,
    parse_service,
)

FULL = """\
# a comment line
bool flag true
byte b 7
char c 65
int8 i8 -128
uint64 u64 18446744073709551615
float32 f 1.5
float64 d -2.5e-3
string s "quoted # not a comment"
string<=5 bounded 'abc'
wstring w
int32[3] fixed [1, 2, 3]
int32[<=4] bounded_seq [1, 2]
float64[] seq
string[] names ["a", 'b,c']
string<=3[<=2] tiny
Header header
geometry_msgs/Point p
Other other  # trailing comment
int32 ANSWER = 42
string GREETING=hello world
bool YES=1
"""


def test_full_grammar() -> None:
    m = parse_message(FULL, 'demo/msg/Full')
    f = {x.name: x for x in m.fields}
    assert f['flag'].default is True
    assert f['b'].default == 7 and f['c'].default == 65
    assert f['u64'].default == 2**64 - 1
    assert f['d'].default == -2.5e-3
    assert f['s'].default == 'quoted # not a comment'
    assert f['bounded'].type == FieldType('string', 5) and f['bounded'].default == 'abc'
    assert f['fixed'].type == FieldType('int32', 0, 'array', 3)
    assert f['fixed'].default == [1, 2, 3]
    assert f['bounded_seq'].type == FieldType('int32', 0, 'bounded', 4)
    assert f['seq'].type == FieldType('float64', 0, 'sequence')
    assert f['names'].default == ['a', 'b,c']
    assert f['tiny'].type == FieldType('string', 3, 'bounded', 2)
    assert f['header'].type.base == 'std_msgs/msg/Header'
    assert f['p'].type.base == 'geometry_msgs/msg/Point'
    assert f['other'].type.base == 'demo/msg/Other'
    assert m.constants == [
        Constant('ANSWER', 'int32', 42),
        Constant('GREETING', 'string', 'hello world'),
        Constant('YES', 'bool', True),
    ]
    assert str(f['tiny'].type) == 'string<=3[<=2]'
    assert str(f['p'].type) == 'geometry_msgs/Point'


def test_service_and_action_sections() -> None:
    s = parse_service('int64 a\n---\nint64 sum\n', 'p/srv/S')
    assert s.request.name == 'p/srv/S_Request' and s.response.fields[0].name == 'sum'
    a = parse_action('int32 order\n---\n---\nint32[] seq\n', 'p/action/A')
    assert a.result.fields == [] and a.feedback.fields[0].name == 'seq'


@pytest.mark.parametrize(
    ('text', 'problem'),
    [
        ('int32', "expected '<type> <name>'"),
        ('int33 x', "invalid type name 'int33'"),
        ('int8 x 300', 'out of range for int8'),
        ('bool x maybe', 'is not a bool'),
        ('int32 BadName', 'invalid field name'),
        ('int32 lower = 1', 'invalid constant name'),
        ('int32[2] x [1]', 'exactly 2 values'),
        ('int32[<=1] x [1, 2]', 'bound is 1'),
        ('string<=2 x "abc"', 'exceeds its bound'),
        ('int32[0] x', 'array size must be positive'),
        ('int32<=3 x', 'only strings can be bounded'),
        ('geometry_msgs/Point p 5', 'cannot have default values'),
        ('int32 x\nint32 x', "duplicate name 'x'"),
        ('int32[] X = 1', 'primitive, non-array type'),
        ('float32 x abc', 'is not a number'),
    ],
)
def test_errors_name_file_line_and_problem(text: str, problem: str) -> None:
    with pytest.raises(InterfaceError) as err:
        parse_message('# header\n' + text, 'demo/msg/Bad', source='Bad.msg')
    message = str(err.value)
    assert message.startswith('Bad.msg:')
    assert problem in message
    line = int(message.split(':')[1])
    assert line >= 2


def test_wrong_separator_count() -> None:
    with pytest.raises(InterfaceError, match="expected 1 '---' separator"):
        parse_service('int32 a\n', 'p/srv/S', source='S.srv')
    with pytest.raises(InterfaceError, match="expected 2 '---'"):
        parse_action('int32 a\n---\n', 'p/action/A', source='A.action')
