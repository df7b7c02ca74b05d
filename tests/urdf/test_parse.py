"""parse_urdf: a description read as urdfdom reads it (materials, mimic joints, the tree), and
hostile or broken descriptions refused in one line."""

from __future__ import annotations

import math

import pytest

from ros2lite.urdf import Geometry, Mimic, UrdfError, parse_urdf
from ros2lite.urdf.parse import MAX_URDF_CHARS
from tests.urdf.robots import ARM


def test_a_robot_with_everything() -> None:
    robot = parse_urdf(ARM)
    assert robot.name == 'arm'
    assert robot.root == 'base_link'
    assert list(robot.links)[:3] == ['base_link', 'shoulder', 'forearm']
    base = robot.links['base_link']
    assert base.visuals[0].geometry == Geometry('box', size=(0.4, 0.3, 0.1))
    assert base.visuals[0].xyz == (0.0, 0.0, 0.05)
    assert base.visuals[0].rgba == (0.0, 0.0, 0.8, 1.0)  # a top-level material, by name
    assert base.collisions[0].geometry.kind == 'box'
    assert base.collisions[0].rgba is None
    shoulder = robot.links['shoulder'].visuals[0]
    assert (shoulder.geometry.kind, shoulder.geometry.radius, shoulder.geometry.length) == (
        'cylinder',
        0.05,
        0.3,
    )
    assert shoulder.rgba == (1.0, 1.0, 1.0, 1.0)
    forearm = robot.links['forearm'].visuals[0]
    # an inline material of another link, named here
    assert forearm.rgba == (1.0, 1.0, 1.0, 1.0)
    assert forearm.geometry.filename == 'package://arm_description/meshes/forearm.stl'
    assert forearm.geometry.scale == (0.001, 0.001, 0.001)
    assert robot.links['slider'].visuals[0].geometry.radius == 0.02
    elbow = robot.joints['elbow']
    assert (elbow.type, elbow.parent, elbow.child) == ('revolute', 'shoulder', 'forearm')
    assert (elbow.lower, elbow.upper, elbow.effort, elbow.velocity) == (-1.5, 1.5, 10.0, 1.0)
    assert elbow.axis == (0.0, 1.0, 0.0) and elbow.moving
    assert robot.joints['slide'].axis == (1.0, 0.0, 0.0)  # normalised
    assert robot.joints['finger_right_joint'].mimic == Mimic('finger_left_joint', -1.0, 0.0)
    assert robot.joints['wheel_joint'].axis == (0.0, 0.0, 1.0)
    assert not robot.joints['camera_mount'].moving
    assert robot.joints['base_to_shoulder'].rpy[2] == pytest.approx(math.pi / 2)
    assert [g.get('reference') for g in robot.gazebo] == ['wheel']
    assert robot.materials == {'blue': (0.0, 0.0, 0.8, 1.0), 'white': (1.0, 1.0, 1.0, 1.0)}
    assert [j.name for j in robot.child_joints('slider')] == [
        'finger_left_joint',
        'finger_right_joint',
    ]


def test_a_single_link_and_namespaced_xacro_leftovers() -> None:
    robot = parse_urdf(
        '<?xml version="1.0" encoding="utf-8"?>\n'
        '<robot name="one" xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<!-- a comment --><link name="only"/></robot>'
    )
    assert (robot.root, list(robot.links), robot.joints) == ('only', ['only'], {})


_LINKS = '<link name="a"/><link name="b"/>'
_ABC = '<robot name="x"><link name="a"/><link name="b"/><link name="c"/>'


def _joint(name: str, kind: str, parent: str, child: str, inner: str = '') -> str:
    return (
        f'<joint name="{name}" type="{kind}"><parent link="{parent}"/>'
        f'<child link="{child}"/>{inner}</joint>'
    )


def _ab(joint: str) -> str:
    return f'<robot name="x">{_LINKS}{joint}</robot>'


def _visual(geometry: str) -> str:
    return f'<robot name="x"><link name="a"><visual>{geometry}</visual></link></robot>'


BROKEN = [
    ('', 'is empty'),
    ('<robot name="x"><link name="a"></robot>', 'not well-formed XML: mismatched tag (line 1'),
    ('<urdf name="x"/>', 'the top element is <urdf>, not <robot>'),
    ('<robot><link name="a"/></robot>', '<robot> has no name'),
    ('<robot name="x"/>', "Robot 'x' has no links"),
    ('<robot name="x"><link name="a"/><link name="a"/></robot>', "Two links are named 'a'"),
    (f'<robot name="x">{_LINKS}</robot>', "2 root links: 'a', 'b'"),
    (
        _ab(_joint('j', 'hinge', 'a', 'b')),
        "joint 'j': unknown type 'hinge'",
    ),
    (
        _ab(_joint('j', 'fixed', 'a', 'c')),
        "child link 'c' is not a link of the robot",
    ),
    (
        _ab(_joint('j', 'revolute', 'a', 'b')),
        'a revolute joint needs a <limit>',
    ),
    (
        _ab(_joint('j', 'fixed', 'a', 'b', "<origin xyz='1 2'/>")),
        "origin xyz: '1 2' is not 3 numbers",
    ),
    (
        _ab(_joint('j', 'fixed', 'a', 'b', "<origin rpy='1 nan 2'/>")),
        'is not a finite number',
    ),
    (
        _ab(_joint('j', 'continuous', 'a', 'b', "<axis xyz='0 0 0'/>")),
        'the axis is the zero vector',
    ),
    (
        _ab(_joint('j', 'continuous', 'a', 'b', "<mimic joint='k'/>")),
        "mimics 'k', which is not a joint",
    ),
    (
        _ABC
        + _joint('j', 'continuous', 'a', 'b', "<mimic joint='k'/>")
        + _joint('k', 'continuous', 'a', 'c', "<mimic joint='j'/>")
        + '</robot>',
        'Mimic joints form a loop: j -> k -> j',
    ),
    (
        _ABC + _joint('j', 'fixed', 'b', 'c') + _joint('k', 'fixed', 'c', 'b') + '</robot>',
        "Link 'b' is not connected to the root",
    ),
    (
        _ABC + _joint('j', 'fixed', 'a', 'c') + _joint('k', 'fixed', 'b', 'c') + '</robot>',
        "Link 'c' is the child of two joints ('j' and 'k')",
    ),
    (
        '<robot name="x"><link name="a"><visual/></link></robot>',
        "link 'a' visual has no <geometry>",
    ),
    (_visual('<geometry><capsule/></geometry>'), 'unknown geometry <capsule>'),
    (_visual('<geometry><box size="1 -1 1"/></geometry>'), 'sizes must not be negative'),
    (_visual('<geometry><mesh/></geometry>'), '<mesh> has no filename'),
    (_visual('<geometry><box/><sphere radius="1"/></geometry>'), 'exactly one shape, not 2'),
    (
        '<robot name="x"><material name="m"><color rgba="1 1 2 1"/></material><link name="a"/>'
        '</robot>',
        "material 'm': color rgba values must be within 0 and 1",
    ),
]


@pytest.mark.parametrize(('text', 'why'), BROKEN)
def test_broken_descriptions_are_named_in_one_line(text: str, why: str) -> None:
    with pytest.raises(UrdfError) as caught:
        parse_urdf(text)
    message = str(caught.value)
    assert why in message
    assert '\n' not in message


def test_hostile_descriptions_are_refused() -> None:
    laughs = (
        '<?xml version="1.0"?><!DOCTYPE robot [<!ENTITY a "aaaaaaaaaa">'
        '<!ENTITY b "&a;&a;&a;&a;&a;&a;&a;&a;&a;&a;">]><robot name="&b;"><link name="l"/></robot>'
    )
    with pytest.raises(UrdfError, match='declares a DTD or an entity: refused'):
        parse_urdf(laughs)
    external = (
        '<!DOCTYPE robot SYSTEM "file:///etc/passwd"><robot name="x"><link name="l"/></robot>'
    )
    with pytest.raises(UrdfError, match='refused'):
        parse_urdf(external)
    with pytest.raises(UrdfError, match='too large'):
        parse_urdf(' ' * (MAX_URDF_CHARS + 1))
    with pytest.raises(UrdfError, match='is text, not bytes'):
        parse_urdf(b'<robot/>')  # type: ignore[arg-type]
    # a name with a newline is shown escaped, the message stays one line
    with pytest.raises(UrdfError, match=r"Robot 'x\\ny' has no links"):
        parse_urdf('<robot name="x&#10;y"/>')
