"""A robot description as plain immutable values: what `parse_urdf` returns and what the
robot state publisher, the joint state publishers, the viewer and the simulator read.

Lengths in metres, angles in radians, as URDF writes them. Only what a consumer of the model
uses is kept; the raw `<gazebo>` elements stay XML for the simulator to read as it likes.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

__all__ = ['JOINT_TYPES', 'MOVING_TYPES', 'Geometry', 'Joint', 'Link', 'Mimic', 'Robot', 'Visual']

Vec3 = tuple[float, float, float]
Rgba = tuple[float, float, float, float]

# URDF's joint types; a state publisher moves only the last three (floating and planar joints
# have no single position: robot_state_publisher keeps them at their origin)
JOINT_TYPES = ('fixed', 'floating', 'planar', 'revolute', 'continuous', 'prismatic')
MOVING_TYPES = ('revolute', 'continuous', 'prismatic')


@dataclass(frozen=True, slots=True)
class Geometry:
    """A shape: `kind` is box (`size`), cylinder (`radius`, `length`), sphere (`radius`) or
    mesh (`filename` as written, `scale`)."""

    kind: str
    size: Vec3 = (0.0, 0.0, 0.0)
    radius: float = 0.0
    length: float = 0.0
    filename: str = ''
    scale: Vec3 = (1.0, 1.0, 1.0)


@dataclass(frozen=True, slots=True)
class Visual:
    """A visual or collision element: its shape placed in the link's frame, and its colour
    (materials resolved; None where the description gives none)."""

    geometry: Geometry
    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)
    rgba: Rgba | None = None
    material: str = ''
    texture: str = ''
    name: str = ''


@dataclass(frozen=True, slots=True)
class Link:
    """A rigid body, its frame named by `name`."""

    name: str
    visuals: tuple[Visual, ...] = ()
    collisions: tuple[Visual, ...] = ()


@dataclass(frozen=True, slots=True)
class Mimic:
    """This joint follows `joint`: position = multiplier * theirs + offset."""

    joint: str
    multiplier: float = 1.0
    offset: float = 0.0


@dataclass(frozen=True, slots=True)
class Joint:
    """A joint from `parent` to `child`: at position 0 the child's frame is the parent's moved
    by (`xyz`, `rpy`); moving joints turn about or slide along `axis` (a unit vector)."""

    name: str
    type: str
    parent: str
    child: str
    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)
    axis: Vec3 = (1.0, 0.0, 0.0)
    lower: float = 0.0
    upper: float = 0.0
    effort: float = 0.0
    velocity: float = 0.0
    mimic: Mimic | None = None

    @property
    def moving(self) -> bool:
        """Whether a joint state moves it (revolute, continuous, prismatic)."""
        return self.type in MOVING_TYPES


@dataclass(frozen=True, slots=True)
class Robot:
    """A whole description: links and joints by name (in document order), the root link (the
    one no joint has as child), and the raw `<gazebo>` elements."""

    name: str
    links: dict[str, Link]
    joints: dict[str, Joint]
    root: str
    gazebo: tuple[ET.Element, ...] = ()
    materials: dict[str, Rgba] = field(default_factory=dict)

    def child_joints(self, link: str) -> list[Joint]:
        """The joints whose parent is `link`, in document order."""
        return [j for j in self.joints.values() if j.parent == link]
