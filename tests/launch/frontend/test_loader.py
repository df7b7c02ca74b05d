"""XML and YAML launch files: the same launch from either format, and clear errors."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite.launch.errors import InvalidFrontendLaunchFileError
from ros2lite.launch.flow import IncludeLaunchDescription
from ros2lite.launch.frontend.builders import split_words
from ros2lite.launch.frontend.loader import load_frontend_file
from ros2lite.launch.frontend.substitutions import parse_substitutions
from ros2lite.launch.introspection import format_arguments
from tests.launch.helpers import run_launch

XML = """<launch>
  <arg name="word" default="hi" description="what to say"/>
  <let name="twice" value="$(var word)$(var word)"/>
  <executable cmd="sh -c 'echo &quot;$(var twice)&quot; $VAR'" name="say" output="screen">
    <env name="VAR" value="from-env"/>
  </executable>
  <group scoped="true" if="true">
    <let name="word" value="inner"/>
    <log message="in group: $(var word)"/>
  </group>
  <log message="after: $(var word) in $(dirname)"/>
  <timer period="0.1"><log message="later"/></timer>
  <log message="skipped" unless="true"/>
</launch>
"""

YAML = """launch:
- arg: {name: word, default: hi, description: what to say}
- let: {name: twice, value: $(var word)$(var word)}
- executable:
    cmd: sh -c 'echo "$(var twice)" $VAR'
    name: say
    output: screen
    env: [{name: VAR, value: from-env}]
- group:
    scoped: true
    if: 'true'
    children:
    - let: {name: word, value: inner}
    - log: {message: 'in group: $(var word)'}
- log: {message: 'after: $(var word) in $(dirname)'}
- timer:
    period: 0.1
    children:
    - log: {message: later}
- log: {message: skipped, unless: 'true'}
"""


@pytest.mark.parametrize(('suffix', 'text'), [('.launch.xml', XML), ('.launch.yaml', YAML)])
def test_same_launch_in_both_formats(tmp_path: Path, suffix: str, text: str) -> None:
    path = tmp_path / f'talk{suffix}'
    path.write_text(text)
    description = load_frontend_file(path)
    assert format_arguments(description) == (
        "Arguments (pass arguments as '<name>:=<value>'):\n\n    'word':\n        what to say\n"
        "        (default: 'hi')"
    )
    code, lines, _ = run_launch([description], tmp_path)
    assert code == 0, lines
    assert '[say-1] hihi from-env' in lines
    user = [line.split(': ', 1)[1] for line in lines if '[launch.user]' in line]
    assert user == ['in group: inner', f'after: hi in {tmp_path}', 'later']


def test_node_params_and_include(tmp_path: Path) -> None:
    path = tmp_path / 'n.launch.xml'
    path.write_text(
        '<launch>\n'
        '  <node pkg="demo_nodes_py" exec="talker" name="t" namespace="ns" args="-a \'b c\'">\n'
        '    <param name="rate" value="5"/>\n'
        '    <param name="list" value="1,2" value-sep=","/>\n'
        '    <param name="group"><param name="inner" value="x"/></param>\n'
        '    <param from="$(dirname)/p.yaml"/>\n'
        '    <remap from="chatter" to="words"/>\n'
        '  </node>\n'
        '  <include file="$(dirname)/other.launch.py"><arg name="k" value="v"/></include>\n'
        '</launch>\n'
    )
    description = load_frontend_file(path)
    node, include = description.entities
    assert node.parameters[0]['rate'][0].text == '5'
    assert [p[0].text for p in node.parameters[1]['list']] == ['1', '2']
    assert node.parameters[2]['group']['inner'][0].text == 'x'
    assert [s.describe() for s in node.parameters[3]] == ['ThisLaunchFileDir()', "'/p.yaml'"]
    assert [[s.text for s in w] for w in node.node_arguments] == [['-a'], ['b c']]
    assert isinstance(include, IncludeLaunchDescription)
    assert [(k[0].text, v[0].text) for k, v in include.launch_arguments] == [('k', 'v')]


def test_split_words_keeps_substitutions_inside_quotes() -> None:
    words = split_words(parse_substitutions("a 'b $(var x) c' d$(var y)"))
    assert [[s.describe() for s in w] for w in words] == [
        ["'a'"],
        ["'b '", "LaunchConfig('x')", "' c'"],
        ["'d'", "LaunchConfig('y')"],
    ]


@pytest.mark.parametrize(
    ('name', 'text', 'error'),
    [
        ('a.xml', '<launch><nodes/></launch>', '<nodes>: unknown launch element'),
        ('b.xml', '<robot/>', 'the root element is <robot>, not <launch>'),
        ('c.xml', '<launch><arg/></launch>', "<arg>: missing attribute 'name'"),
        ('d.xml', '<launch>', 'not valid XML'),
        ('e.yaml', 'nodes: []', "a YAML launch file starts with 'launch:'"),
        ('f.yaml', 'launch: [{node: {pkg: a}, arg: {}}]', 'each action is a mapping with one key'),
        ('g.yaml', 'launch:\n- group: {scoped: maybe}', "'scoped' must be true or false"),
        ('h.yaml', 'launch: [: :', 'not valid YAML'),
        (
            'i.yaml',
            'a: &a [x, x, x, x, x, x, x, x, x, x]\n'
            + ''.join(
                f'{n}: &{n} [*{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}]\n'
                for p, n in zip('abcdefgh', 'bcdefghi', strict=True)
            )
            + 'launch: []\n',
            'expands to more than',
        ),
    ],
)
def test_errors(tmp_path: Path, name: str, text: str, error: str) -> None:
    path = tmp_path / name
    path.write_text(text)
    with pytest.raises(InvalidFrontendLaunchFileError) as info:
        load_frontend_file(path)
    assert error in str(info.value)
    assert '\n' not in str(info.value)  # one line
