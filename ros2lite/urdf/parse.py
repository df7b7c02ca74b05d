"""URDF text to a `Robot`, read as robot_state_publisher's parser (urdfdom) reads it, with
the description treated as hostile input: a size bound, no DTD (so no entity of any kind),
every number checked, and a broken description named in one line.

Materials are resolved into each visual's colour: a visual's own `<color>`, else the material
of that name declared at the top level or inline in any other visual (as urdfdom collects
them). The tree is checked: one root link, every other link the child of exactly one joint,
every link reachable, mimic joints naming real joints and no mimic loop.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import replace
from xml.parsers import expat

from ros2lite.urdf.errors import UrdfError
from ros2lite.urdf.model import JOINT_TYPES, Geometry, Joint, Link, Mimic, Rgba, Robot, Vec3, Visual

__all__ = ['MAX_URDF_CHARS', 'parse_urdf', 'read_xml']

# a description larger than this is refused (the largest real robots' are a few MB)
MAX_URDF_CHARS = 32 * 1024 * 1024


def parse_urdf(text: str) -> Robot:
    """The robot `text` describes; UrdfError (one line) when it is not a usable URDF."""
    top = read_xml(text, 'robot description')
    if top.tag != 'robot':
        raise UrdfError(f'Not a URDF: the top element is <{_shown(top.tag)}>, not <robot>')
    name = _required(top, 'name', 'robot')
    materials = _materials(top)
    links: dict[str, Link] = {}
    for element in top.findall('link'):
        link = _link(element, materials)
        if link.name in links:
            raise UrdfError(f"Two links are named '{_shown(link.name)}'")
        links[link.name] = link
    if not links:
        raise UrdfError(f"Robot '{_shown(name)}' has no links")
    links = {n: _resolve_materials(link, materials) for n, link in links.items()}
    joints: dict[str, Joint] = {}
    for element in top.findall('joint'):
        joint = _joint(element, links)
        if joint.name in joints:
            raise UrdfError(f"Two joints are named '{_shown(joint.name)}'")
        joints[joint.name] = joint
    root = _root(links, joints)
    _check_mimics(joints)
    return Robot(
        name=name,
        links=links,
        joints=joints,
        root=root,
        gazebo=tuple(top.findall('gazebo')),
        materials={n: rgba for n, (rgba, _) in materials.items() if rgba is not None},
    )


def read_xml(text: str, what: str = 'document') -> ET.Element:
    """The element tree of `text`, refusing a DTD, an oversized or a malformed document."""
    if not isinstance(text, str):
        raise UrdfError(f'A {what} is text, not {type(text).__name__}')
    if len(text) > MAX_URDF_CHARS:
        raise UrdfError(
            f'The {what} is too large ({len(text)} characters, at most {MAX_URDF_CHARS})'
        )
    if not text.strip():
        raise UrdfError(f'The {what} is empty')
    builder = ET.TreeBuilder()
    parser = expat.ParserCreate()

    def refuse(*_: object) -> None:
        raise UrdfError(f'The {what} declares a DTD or an entity: refused')

    parser.StartDoctypeDeclHandler = refuse
    parser.EntityDeclHandler = refuse
    parser.StartElementHandler = builder.start
    parser.EndElementHandler = builder.end
    parser.CharacterDataHandler = builder.data
    parser.buffer_text = True
    try:
        parser.Parse(text, True)
    except expat.ExpatError as e:
        raise UrdfError(
            f'The {what} is not well-formed XML: {expat.ErrorString(e.code)} '
            f'(line {e.lineno}, column {e.offset + 1})'
        ) from None
    return builder.close()


# -- materials and links ------------------------------------------------------------------------
# name -> (rgba or None, texture filename)
_Materials = dict[str, tuple[Rgba | None, str]]


def _materials(top: ET.Element) -> _Materials:
    materials: _Materials = {}
    for element in top.findall('material'):
        name = _required(element, 'name', 'material')
        materials.setdefault(name, _material_value(element, f"material '{_shown(name)}'"))
    # materials declared inline with a colour can be named by other visuals too
    for visual in top.findall('link/visual/material'):
        name = visual.get('name', '')
        if name and name not in materials:
            rgba, texture = _material_value(visual, f"material '{_shown(name)}'")
            if rgba is not None or texture:
                materials[name] = (rgba, texture)
    return materials


def _material_value(element: ET.Element, where: str) -> tuple[Rgba | None, str]:
    rgba: Rgba | None = None
    color = element.find('color')
    if color is not None:
        r, g, b, a = _floats(_required(color, 'rgba', f'{where} color'), 4, f'{where} color rgba')
        if not all(0.0 <= v <= 1.0 for v in (r, g, b, a)):
            raise UrdfError(f'{where}: color rgba values must be within 0 and 1')
        rgba = (r, g, b, a)
    texture = element.find('texture')
    return rgba, (texture.get('filename', '') if texture is not None else '')


def _link(element: ET.Element, materials: _Materials) -> Link:
    name = _required(element, 'name', 'link')
    where = f"link '{_shown(name)}'"
    visuals = tuple(_visual(v, f'{where} visual') for v in element.findall('visual'))
    collisions = tuple(_visual(c, f'{where} collision') for c in element.findall('collision'))
    return Link(name=name, visuals=visuals, collisions=collisions)


def _visual(element: ET.Element, where: str) -> Visual:
    xyz, rpy = _origin(element, where)
    shape = element.find('geometry')
    if shape is None:
        raise UrdfError(f'{where} has no <geometry>')
    rgba: Rgba | None = None
    material, texture = '', ''
    found = element.find('material')
    if found is not None:
        material = found.get('name', '')
        rgba, texture = _material_value(found, f'{where} material')
    return Visual(
        geometry=_geometry(shape, where),
        xyz=xyz,
        rpy=rpy,
        rgba=rgba,
        material=material,
        texture=texture,
        name=element.get('name', ''),
    )


def _resolve_materials(link: Link, materials: _Materials) -> Link:
    def resolved(visual: Visual) -> Visual:
        if visual.rgba is not None or not visual.material or visual.material not in materials:
            return visual  # a name nothing declares keeps no colour (the viewer's default)
        rgba, texture = materials[visual.material]
        return replace(visual, rgba=rgba, texture=visual.texture or texture)

    return replace(link, visuals=tuple(resolved(v) for v in link.visuals))


def _geometry(element: ET.Element, where: str) -> Geometry:
    shapes = [child for child in element if isinstance(child.tag, str)]
    if len(shapes) != 1:
        raise UrdfError(f'{where}: <geometry> must hold exactly one shape, not {len(shapes)}')
    shape = shapes[0]
    kind = shape.tag
    what = f'{where} {_shown(kind)}'
    if kind == 'box':
        size = _vec(_required(shape, 'size', what), f'{what} size')
        return Geometry(kind, size=_nonnegative(size, f'{what} size'))
    if kind == 'cylinder':
        radius = _number(_required(shape, 'radius', what), f'{what} radius')
        length = _number(_required(shape, 'length', what), f'{what} length')
        _nonnegative((radius, length), what)
        return Geometry(kind, radius=radius, length=length)
    if kind == 'sphere':
        radius = _number(_required(shape, 'radius', what), f'{what} radius')
        _nonnegative((radius,), what)
        return Geometry(kind, radius=radius)
    if kind == 'mesh':
        filename = _required(shape, 'filename', what)
        scale = shape.get('scale')
        return Geometry(
            kind,
            filename=filename,
            scale=_vec(scale, f'{what} scale') if scale is not None else (1.0, 1.0, 1.0),
        )
    raise UrdfError(f'{where}: unknown geometry <{_shown(kind)}> (box, cylinder, sphere, mesh)')


# -- joints and the tree ------------------------------------------------------------------------
def _joint(element: ET.Element, links: dict[str, Link]) -> Joint:
    name = _required(element, 'name', 'joint')
    where = f"joint '{_shown(name)}'"
    kind = _required(element, 'type', where)
    if kind not in JOINT_TYPES:
        raise UrdfError(f"{where}: unknown type '{_shown(kind)}' ({', '.join(JOINT_TYPES)})")
    ends = []
    for end in ('parent', 'child'):
        found = element.find(end)
        if found is None:
            raise UrdfError(f'{where} has no <{end}>')
        link = _required(found, 'link', f'{where} {end}')
        if link not in links:
            raise UrdfError(f"{where}: {end} link '{_shown(link)}' is not a link of the robot")
        ends.append(link)
    xyz, rpy = _origin(element, where)
    axis: Vec3 = (1.0, 0.0, 0.0)
    found = element.find('axis')
    if found is not None and found.get('xyz') is not None:
        axis = _unit(_vec(found.get('xyz', ''), f'{where} axis'), where)
    lower = upper = effort = velocity = 0.0
    limit = element.find('limit')
    if limit is not None:
        lower, upper, effort, velocity = (
            _number(limit.get(key, '0'), f'{where} limit {key}')
            for key in ('lower', 'upper', 'effort', 'velocity')
        )
    elif kind in ('revolute', 'prismatic'):
        raise UrdfError(f'{where}: a {kind} joint needs a <limit>')
    mimic = None
    found = element.find('mimic')
    if found is not None:
        mimic = Mimic(
            joint=_required(found, 'joint', f'{where} mimic'),
            multiplier=_number(found.get('multiplier', '1'), f'{where} mimic multiplier'),
            offset=_number(found.get('offset', '0'), f'{where} mimic offset'),
        )
    return Joint(
        name=name,
        type=kind,
        parent=ends[0],
        child=ends[1],
        xyz=xyz,
        rpy=rpy,
        axis=axis,
        lower=lower,
        upper=upper,
        effort=effort,
        velocity=velocity,
        mimic=mimic,
    )


def _root(links: dict[str, Link], joints: dict[str, Joint]) -> str:
    parent_of: dict[str, str] = {}
    for joint in joints.values():
        if joint.child in parent_of:
            raise UrdfError(
                f"Link '{_shown(joint.child)}' is the child of two joints "
                f"('{_shown(parent_of[joint.child])}' and '{_shown(joint.name)}')"
            )
        parent_of[joint.child] = joint.name
    roots = [name for name in links if name not in parent_of]
    if not roots:
        raise UrdfError('The robot has no root link: its joints form a loop')
    if len(roots) > 1:
        raise UrdfError(
            f'The robot has {len(roots)} root links: ' + ', '.join(map(repr, roots[:5]))
        )
    children: dict[str, list[str]] = {}
    for joint in joints.values():
        children.setdefault(joint.parent, []).append(joint.child)
    reached, todo = {roots[0]}, [roots[0]]
    while todo:
        for child in children.get(todo.pop(), ()):
            if child not in reached:
                reached.add(child)
                todo.append(child)
    lost = [name for name in links if name not in reached]
    if lost:
        raise UrdfError(f"Link '{_shown(lost[0])}' is not connected to the root (a joint loop)")
    return roots[0]


def _check_mimics(joints: dict[str, Joint]) -> None:
    for joint in joints.values():
        seen = [joint.name]
        current = joint
        while current.mimic is not None:
            target = joints.get(current.mimic.joint)
            if target is None:
                raise UrdfError(
                    f"joint '{_shown(current.name)}' mimics '{_shown(current.mimic.joint)}', "
                    'which is not a joint of the robot'
                )
            if target.name in seen:
                raise UrdfError(f"Mimic joints form a loop: {' -> '.join([*seen, target.name])}")
            seen.append(target.name)
            current = target


# -- values -------------------------------------------------------------------------------------
def _origin(element: ET.Element, where: str) -> tuple[Vec3, Vec3]:
    origin = element.find('origin')
    if origin is None:
        return (0.0, 0.0, 0.0), (0.0, 0.0, 0.0)
    xyz = _vec(origin.get('xyz', '0 0 0'), f'{where} origin xyz')
    rpy = _vec(origin.get('rpy', '0 0 0'), f'{where} origin rpy')
    return xyz, rpy


def _required(element: ET.Element, key: str, where: str) -> str:
    value = element.get(key)
    if value is None or not value.strip():
        raise UrdfError(f'{where}: <{_shown(element.tag)}> has no {key}')
    return value.strip()


def _number(text: str, where: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise UrdfError(f"{where}: '{_shown(text)}' is not a number") from None
    if not math.isfinite(value):
        raise UrdfError(f"{where}: '{_shown(text)}' is not a finite number")
    return value


def _floats(text: str, count: int, where: str) -> tuple[float, ...]:
    parts = text.split()
    if len(parts) != count:
        raise UrdfError(f"{where}: '{_shown(text)}' is not {count} numbers")
    return tuple(_number(part, where) for part in parts)


def _vec(text: str, where: str) -> Vec3:
    x, y, z = _floats(text, 3, where)
    return (x, y, z)


def _nonnegative(values: tuple[float, ...], where: str) -> Vec3:
    if any(v < 0 for v in values):
        raise UrdfError(f'{where}: sizes must not be negative')
    padded = (*values, 0.0, 0.0, 0.0)
    return (padded[0], padded[1], padded[2])


def _unit(axis: Vec3, where: str) -> Vec3:
    norm = math.sqrt(axis[0] ** 2 + axis[1] ** 2 + axis[2] ** 2)
    if norm == 0.0:
        raise UrdfError(f'{where}: the axis is the zero vector')
    return (axis[0] / norm, axis[1] / norm, axis[2] / norm)


def _shown(text: str) -> str:
    """A value for a one-line message: printable, bounded."""
    shown = str(text).encode('unicode_escape').decode('ascii')
    return shown if len(shown) <= 80 else shown[:80] + '…'
