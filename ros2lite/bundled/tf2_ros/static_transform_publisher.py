"""`static_transform_publisher`: sends one static transform on `/tf_static` until stopped.

Takes tf2_ros's flags (`--x --y --z`, `--roll --pitch --yaw` or `--qx --qy --qz --qw`,
`--frame-id`, `--child-frame-id`) and its deprecated positional forms `x y z yaw pitch roll
frame child` and `x y z qx qy qz qw frame child`. Like tf2_ros's program, the node
(`static_transform_publisher_<random>`) holds the transform as read-only parameters and a bad
command line gets one error line and the usage.
"""

from __future__ import annotations

import re
import secrets
import string
import sys
from dataclasses import dataclass, field

from ros2lite.bundled.display import own_arguments
from ros2lite.bundled.runner import run_node
from ros2lite.exceptions import Ros2liteError
from ros2lite.logging import RcutilsLogger
from ros2lite.node import Node
from ros2lite.tf2.math import quaternion_from_rpy

USAGE = (
    'usage: static_transform_publisher [--x X] [--y Y] [--z Z] [--qx QX] [--qy QY] '
    '[--qz QZ] [--qw QW] [--roll ROLL] [--pitch PITCH] [--yaw YAW] --frame-id FRAME_ID '
    '--child-frame-id CHILD_FRAME_ID\n\n'
    'A command line utility for manually sending a static transform.\n\n'
    'If no translation or orientation is provided, the identity transform will be published.'
    '\n\nThe translation offsets are in meters.\n\n'
    'The rotation may be provided with roll, pitch, yaw euler angles in radians, or as a '
    'quaternion.\n\n'
    'required arguments:\n'
    '  --frame-id FRAME_ID parent frame\n'
    '  --child-frame-id CHILD_FRAME_ID child frame id\n\n'
    'optional arguments:\n'
    '  --x X                 x component of translation\n'
    '  --y Y                 y component of translation\n'
    '  --z Z                 z component of translation\n'
    '  --qx QX               x component of quaternion rotation\n'
    '  --qy QY               y component of quaternion rotation\n'
    '  --qz QZ               z component of quaternion rotation\n'
    '  --qw QW               w component of quaternion rotation\n'
    '  --roll ROLL           roll component Euler rotation\n'
    '  --pitch PITCH         pitch component Euler rotation\n'
    '  --yaw YAW             yaw component Euler rotation'
)

_NUMBERS = {
    '--x': 'x',
    '--y': 'y',
    '--z': 'z',
    '--qx': 'qx',
    '--qy': 'qy',
    '--qz': 'qz',
    '--qw': 'qw',
    '--roll': 'roll',
    '--pitch': 'pitch',
    '--yaw': 'yaw',
}
_QUAT = ('qx', 'qy', 'qz', 'qw')
_RPY = ('roll', 'pitch', 'yaw')
_TRANS = ('x', 'y', 'z')
_OLD_STYLE = 'Old-style arguments are deprecated; see --help for new-style arguments'

# tf2_ros's program logs through rcutils' unnamed macros: its lines read `[WARN] [time] []: ...`
_log = RcutilsLogger()


class UsageError(Ros2liteError, ValueError):
    """The command line cannot be understood (the text says why, as tf2_ros words it)."""


@dataclass
class StaticTransform:
    """What the command line asks to publish."""

    translation: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rotation: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)
    frame_id: str = ''
    child_frame_id: str = ''
    old_style: bool = False
    help: bool = False
    values: dict[str, float] = field(default_factory=dict)


C_FLOAT = re.compile(r'\s*[+-]?(inf(inity)?|nan|(\d+\.?\d*|\.\d+)(e[+-]?\d+)?)', re.I)
"""The start of a text that C's strtod (so std::stod and std::stof) reads as a number."""


def _number(name: str, text: str) -> float:
    """A float the way std::stod reads the start of `text`."""
    match = C_FLOAT.match(text)
    if match is None:
        raise UsageError(f'Failed to parse {name} argument as float')
    return float(match.group(0))


def parse(args: list[str]) -> StaticTransform:
    """The transform of a command line, by tf2_ros's rules; UsageError when it has none."""
    out = StaticTransform()
    values: dict[str, float] = {}
    positional: list[str] = []
    frames = {'--frame-id': '', '--child-frame-id': ''}
    saw_frame = False
    i = 0
    while i < len(args):
        arg = args[i]
        if arg in ('--help', '-h'):
            out.help = True
        elif arg in _NUMBERS or arg in frames:
            if i == len(args) - 1:
                raise UsageError(f'Not enough arguments for {arg}')
            i += 1
            if arg in frames:
                frames[arg] = args[i]
                saw_frame = True
            else:
                values[_NUMBERS[arg]] = _number(arg, args[i])
        else:
            positional.append(arg)
        i += 1
    if out.help:
        return out
    saw_quat = any(k in values for k in _QUAT)
    saw_rpy = any(k in values for k in _RPY)
    saw_trans = any(k in values for k in _TRANS)
    if saw_rpy and saw_quat:
        raise UsageError('Cannot specify both quaternion and Euler rotations')
    if len(positional) in (8, 9):
        out.old_style = True
        _log.warning(_OLD_STYLE)  # before it is checked, as tf2_ros warns
        if saw_frame or saw_trans or saw_quat:
            raise UsageError('Cannot specify both new-style (flags) and old-style (arguments)')
        names = (
            ('x', 'y', 'z', 'yaw', 'pitch', 'roll') if len(positional) == 8 else (*_TRANS, *_QUAT)
        )
        for name, text in zip(names, positional, strict=False):
            values[name] = _number(name, text)
        frames['--frame-id'], frames['--child-frame-id'] = positional[-2:]
        saw_rpy = len(positional) == 8
    elif positional:
        raise UsageError('Extra unparsed arguments on command-line')
    out.translation = (values.get('x', 0.0), values.get('y', 0.0), values.get('z', 0.0))
    if saw_rpy:
        out.rotation = quaternion_from_rpy(
            values.get('roll', 0.0), values.get('pitch', 0.0), values.get('yaw', 0.0)
        )
    else:
        out.rotation = (
            values.get('qx', 0.0),
            values.get('qy', 0.0),
            values.get('qz', 0.0),
            values.get('qw', 1.0),
        )
    out.frame_id, out.child_frame_id = frames['--frame-id'], frames['--child-frame-id']
    if not out.frame_id:
        raise UsageError('Frame id must not be empty')
    if not out.child_frame_id:
        raise UsageError('Child frame id must not be empty')
    out.values = values
    return out


def _unique_name() -> str:
    alphabet = string.digits + string.ascii_letters
    return 'static_transform_publisher_' + ''.join(secrets.choice(alphabet) for _ in range(16))


class StaticTransformPublisher(Node):
    """Holds the transform as read-only parameters and sends it once, latched."""

    def __init__(self, spec: StaticTransform) -> None:
        from ros2lite.msgs.geometry_msgs.msg import TransformStamped
        from ros2lite.msgs.rcl_interfaces.msg import ParameterDescriptor
        from ros2lite.parameter import Parameter
        from ros2lite.tf2 import StaticTransformBroadcaster

        (x, y, z), (qx, qy, qz, qw) = spec.translation, spec.rotation
        given: dict[str, float | str] = {
            'translation.x': x,
            'translation.y': y,
            'translation.z': z,
            'rotation.x': qx,
            'rotation.y': qy,
            'rotation.z': qz,
            'rotation.w': qw,
            'frame_id': spec.frame_id,
            'child_frame_id': spec.child_frame_id,
        }
        super().__init__(
            _unique_name(), parameter_overrides=[Parameter(k, value=v) for k, v in given.items()]
        )
        read_only = ParameterDescriptor(read_only=True)
        defaults: dict[str, float | str] = {
            'translation.x': 0.0,
            'translation.y': 0.0,
            'translation.z': 0.0,
            'rotation.x': 0.0,
            'rotation.y': 0.0,
            'rotation.z': 0.0,
            'rotation.w': 1.0,
            'frame_id': '/frame',
            'child_frame_id': '/child',
        }
        value = {
            name: self.declare_parameter(name, default, read_only).value
            for name, default in defaults.items()
        }
        t = TransformStamped()
        t.header.stamp = self.get_clock().now().to_msg()
        t.header.frame_id = str(value['frame_id'])
        t.child_frame_id = str(value['child_frame_id'])
        tr, rot = t.transform.translation, t.transform.rotation
        tr.x, tr.y, tr.z = (float(value[f'translation.{k}']) for k in 'xyz')
        rot.x, rot.y, rot.z, rot.w = (float(value[f'rotation.{k}']) for k in 'xyzw')
        if t.header.frame_id == t.child_frame_id:
            self.get_logger().error(
                f"cannot publish static transform from '{t.header.frame_id}' to "
                f"'{t.child_frame_id}', exiting"
            )
            raise ValueError('child_frame_id cannot equal frame_id')
        self.broadcaster = StaticTransformBroadcaster(self)
        self.broadcaster.sendTransform(t)
        self.get_logger().info(
            'Spinning until stopped - publishing transform\n'
            f"translation: ('{tr.x:f}', '{tr.y:f}', '{tr.z:f}')\n"
            f"rotation: ('{rot.x:f}', '{rot.y:f}', '{rot.z:f}', '{rot.w:f}')\n"
            f"from '{t.header.frame_id}' to '{t.child_frame_id}'"
        )


def main(args: list[str] | None = None) -> int:
    """`static_transform_publisher`'s entry point."""
    try:
        spec = parse(own_arguments(args))
    except UsageError as e:
        _log.error(f'error parsing command line arguments: {e}')
        print(USAGE, flush=True)
        return 1
    if spec.help:
        print(USAGE, flush=True)
        return 0
    return run_node(lambda: StaticTransformPublisher(spec), args)


if __name__ == '__main__':
    sys.exit(main())
