"""Definition text (the rosbag2 ros2msg schema) and `interface show` rendering."""

from __future__ import annotations

import pytest
from mcap_ros2._dynamic import generate_dynamic

from ros2lite import interfaces as I
from ros2lite.interfaces.registry import default_registry
from ros2lite.interfaces.text import SEPARATOR, show_lines

# mcap-ros2-support has no wstring reader, so types using wstring are checked elsewhere
MESSAGES = [
    n for n in I.list_interfaces() if '/msg/' in n and 'wstring' not in I.definition_text(n)
]


def test_concatenation_order_and_names() -> None:
    text = I.definition_text('geometry_msgs/msg/PoseStamped')
    parts = text.split('\n' + SEPARATOR)
    assert parts[0] == 'std_msgs/Header header\nPose pose\n'
    headers = [p.split('\n', 1)[0] for p in parts[1:]]
    # depth first, siblings sorted, each once, named as written in the referencing file
    assert headers == [
        'MSG: geometry_msgs/Pose',
        'MSG: geometry_msgs/Point',
        'MSG: geometry_msgs/Quaternion',
        'MSG: std_msgs/Header',
        'MSG: builtin_interfaces/Time',
    ]


def test_service_event_uses_srv_text() -> None:
    text = I.definition_text('example_interfaces/srv/AddTwoInts_Event')
    assert (
        text == SEPARATOR + 'SRV: example_interfaces/srv/AddTwoInts\n'
        'int64 a\nint64 b\n---\nint64 sum\n'
    )


@pytest.mark.parametrize('name', MESSAGES)
def test_mcap_ros2_decodes_our_bytes_with_our_schema(name: str) -> None:
    # mcap-ros2-support is an independent parser of both the schema text and the CDR
    decoder = generate_dynamic(name, I.definition_text(name))[name]
    ours = I.get_interface(name)()
    decoded = decoder(I.serialize(ours))
    for field in ours.get_fields_and_field_types():
        assert hasattr(decoded, field)


def test_generated_action_types_get_synthesized_text() -> None:
    # no .msg file exists for these; names stay two-part so ros2msg parsers accept the lines
    text = I.definition_text('example_interfaces/action/Fibonacci_FeedbackMessage')
    assert text == (
        'unique_identifier_msgs/UUID goal_id\nexample_interfaces/Fibonacci_Feedback feedback\n'
        '\n' + SEPARATOR + 'MSG: example_interfaces/Fibonacci_Feedback\nint32[] sequence\n'
        '\n' + SEPARATOR + 'MSG: unique_identifier_msgs/UUID\nuint8[16] uuid\n'
    )


def test_show_expands_nested_types_with_tabs() -> None:
    lines = show_lines('geometry_msgs/msg/PoseStamped', default_registry())
    assert lines[:5] == [
        'std_msgs/Header header',
        '\tbuiltin_interfaces/Time stamp',
        '\t\tint32 sec',
        '\t\tuint32 nanosec',
        '\tstring frame_id',
    ]


def test_show_comment_modes(tmp_path: pytest.TempPathFactory) -> None:
    from pathlib import Path

    from ros2lite.interfaces.registry import BUNDLED, Registry

    root = Path(str(tmp_path))
    (root / 'demo' / 'msg').mkdir(parents=True)
    (root / 'demo' / 'msg' / 'Outer.msg').write_text(
        '# A short, varied, and nested type\nInner inner # Comment - nesting\n\n'
        'int32 X=1 # const comment\n# Trailing comment\n'
    )
    (root / 'demo' / 'msg' / 'Inner.msg').write_text('# inner doc\n\nbool flag # a flag\n')
    reg = Registry([root, BUNDLED])
    # a trailing comment is cut one character before where its text starts: the '#' stays,
    # as the real ros2cli prints it (checked with shared/tools/ros2cli-oracle)
    assert show_lines('demo/msg/Outer', reg) == [
        '# A short, varied, and nested type',
        'Inner inner # Comment - nesting',
        '\tbool flag #',
        '',
        'int32 X=1 # const comment',
        '# Trailing comment',
    ]
    assert show_lines('demo/msg/Outer', reg, all_comments=True) == [
        '# A short, varied, and nested type',
        'Inner inner # Comment - nesting',
        '\t# inner doc',
        '',
        '\tbool flag # a flag',
        '',
        'int32 X=1 # const comment',
        '# Trailing comment',
    ]
    assert show_lines('demo/msg/Outer', reg, no_comments=True) == [
        'Inner inner #',
        '\tbool flag #',
        'int32 X=1 #',
    ]


QUIRKS = [
    '# doc line',
    '#',
    '#[m]',
    '# [m] after unit',
    '  # indented comment',
    '',
    'bool flag # a flag',
    'float64 x # [m]',
    'float64 y # a [m] b',
    'float64 z #',
    'int32 X=1 # const comment',
    'string S="a#b" # str const',
    'Inner inner # nested one',
    'int32\ttabbed\t# tab\there',
    'float64 w ## two hashes',
    'float64 v # [m] [s] two units',
    '#trailing',
]


def test_show_follows_ros2cli_comment_rules_to_the_letter(tmp_path: pytest.TempPathFactory) -> None:
    """ros2cli hands each line alone to rosidl_adapter: a comment emptied by taking out its
    one '[unit]' is no comment, an indented one neither, a trailing one is cut where its
    dedented text first occurs. The expected lines are what the real ros2cli printed for
    these files (shared/tools/ros2cli-oracle, `real ros2 interface show`)."""
    from pathlib import Path

    from ros2lite.interfaces.registry import BUNDLED, Registry

    root = Path(str(tmp_path))
    (root / 'quirk_msgs' / 'msg').mkdir(parents=True)
    (root / 'quirk_msgs' / 'msg' / 'Quirk.msg').write_text('\n'.join(QUIRKS) + '\n')
    (root / 'quirk_msgs' / 'msg' / 'Inner.msg').write_text(
        '# inner doc\n\nbool flag # a flag\n  # indented\nint8 k\n'
    )
    reg = Registry([root, BUNDLED])
    nested = ['\tbool flag #', '\t  # indented', '\tint8 k']
    at = QUIRKS.index('Inner inner # nested one') + 1
    assert show_lines('quirk_msgs/msg/Quirk', reg) == QUIRKS[:at] + nested + QUIRKS[at:]
    nested_all = ['\t# inner doc', '', '\tbool flag # a flag', *nested[1:]]
    assert show_lines('quirk_msgs/msg/Quirk', reg, all_comments=True) == (
        QUIRKS[:at] + nested_all + QUIRKS[at:]
    )
    assert show_lines('quirk_msgs/msg/Quirk', reg, no_comments=True) == [
        '#',
        '#[m]',
        '  # indented comment',
        'bool flag #',
        'float64 x # [m]',
        'float64 y # a [m]',
        'float64 z #',
        'int32 X=1 #',
        'string S="a',
        'Inner inner #',
        *nested,
        'int32\ttabbed\t# tab\the',
        'float64 w ##',
        'float64 v #',
    ]
