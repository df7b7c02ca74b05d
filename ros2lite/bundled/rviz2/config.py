"""What the viewer shows: the display kinds RViz users know, the message types each draws,
and a `.rviz` file read into them (fixed frame, displays with their topics, the camera)."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

from ros2lite.exceptions import Ros2liteError

# RViz's display class (rviz_default_plugins/<kind>) -> the message types it draws
KINDS: dict[str, tuple[str, ...]] = {
    'Grid': (),
    'TF': (),
    'LaserScan': ('sensor_msgs/msg/LaserScan',),
    'PointCloud2': ('sensor_msgs/msg/PointCloud2',),
    'Marker': ('visualization_msgs/msg/Marker',),
    'MarkerArray': ('visualization_msgs/msg/MarkerArray',),
    'Odometry': ('nav_msgs/msg/Odometry',),
    'Path': ('nav_msgs/msg/Path',),
    'Pose': ('geometry_msgs/msg/PoseStamped',),
    'PoseWithCovariance': ('geometry_msgs/msg/PoseWithCovarianceStamped',),
    'PoseArray': ('geometry_msgs/msg/PoseArray',),
    'Map': ('nav_msgs/msg/OccupancyGrid',),
    'Image': ('sensor_msgs/msg/Image', 'sensor_msgs/msg/CompressedImage'),
    'RobotModel': ('std_msgs/msg/String',),
}
TOPIC_KINDS = {t: kind for kind, types in KINDS.items() for t in types if kind != 'RobotModel'}
"""A topic's type -> the display zero configuration gives it (RobotModel only by its name)."""

ROBOT_DESCRIPTION = '/robot_description'


class ConfigError(Ros2liteError, ValueError):
    """A `.rviz` file that cannot be read (one line: which file and why)."""


@dataclasses.dataclass(frozen=True)
class DisplaySpec:
    """One display: its kind, topic (empty for Grid and TF) and whether it starts shown."""

    kind: str
    topic: str = ''
    enabled: bool = True
    name: str = ''


@dataclasses.dataclass(frozen=True)
class View:
    """The camera: where it is and what it looks at, in the fixed frame."""

    position: tuple[float, float, float]
    look_at: tuple[float, float, float]


@dataclasses.dataclass(frozen=True)
class Config:
    """A `.rviz` file's content, as far as it maps onto this viewer."""

    fixed_frame: str = ''
    displays: tuple[DisplaySpec, ...] = ()
    view: View | None = None
    skipped: tuple[str, ...] = ()  # display classes it names that nothing here draws


def load(path: str) -> Config:
    """Read a `.rviz` file (YAML)."""
    from ros2lite.util.safe_yaml import YamlInputError
    from ros2lite.util.safe_yaml import load as load_yaml

    try:
        text = Path(path).read_text(encoding='utf-8')
    except (OSError, UnicodeDecodeError) as e:
        raise ConfigError(f'cannot read {path}: {getattr(e, "strerror", None) or e}') from None
    try:
        doc = load_yaml(text, what=path)
    except YamlInputError as e:
        raise ConfigError(str(e)) from None
    try:
        return parse(doc)
    except ConfigError as e:
        raise ConfigError(f'{path}: {e}') from None


def parse(doc: object) -> Config:
    """A `.rviz` document (as YAML loads it) read into a Config."""
    if not isinstance(doc, dict):
        raise ConfigError('not an RViz configuration (no mapping at the top)')
    manager = doc.get('Visualization Manager', {})
    if not isinstance(manager, dict):
        raise ConfigError("'Visualization Manager' is not a mapping")
    options = manager.get('Global Options', {})
    fixed = options.get('Fixed Frame', '') if isinstance(options, dict) else ''
    displays: list[DisplaySpec] = []
    skipped: list[str] = []
    _collect(manager.get('Displays', []), displays, skipped)
    return Config(
        fixed_frame=str(fixed or ''),
        displays=tuple(displays),
        view=_view(manager.get('Views', {})),
        skipped=tuple(skipped),
    )


def _collect(items: object, out: list[DisplaySpec], skipped: list[str]) -> None:
    """Displays of a list, groups (rviz_common/Group) flattened into it."""
    if items is None:
        return
    if not isinstance(items, list):
        raise ConfigError("'Displays' is not a list")
    for item in items:
        if not isinstance(item, dict):
            raise ConfigError('a display is not a mapping')
        cls = str(item.get('Class', ''))
        kind = cls.rpartition('/')[2]
        enabled = item.get('Enabled', True) is not False
        if kind == 'Group':
            _collect(item.get('Displays', []), out, skipped)
            continue
        if kind not in KINDS:
            skipped.append(cls)
            continue
        key = 'Description Topic' if kind == 'RobotModel' else 'Topic'
        topic = _topic(item.get(key))
        if kind == 'RobotModel' and not topic:
            topic = ROBOT_DESCRIPTION
        if KINDS[kind] and not topic:
            raise ConfigError(f'display {item.get("Name", kind)!r} names no topic')
        out.append(DisplaySpec(kind, topic, enabled, str(item.get('Name', kind))))


def _topic(value: object) -> str:
    """A display's topic: `Topic: {Value: /scan}` as rviz2 writes it, or `Topic: /scan`."""
    if isinstance(value, dict):
        value = value.get('Value', '')
    if not isinstance(value, str):
        return ''
    return value if not value or value.startswith('/') else '/' + value


def _number(mapping: dict[object, object], key: str, default: float) -> float:
    value = mapping.get(key, default)
    if not isinstance(value, (int, float)) or isinstance(value, bool):
        raise ConfigError(f'view {key!r} is not a number')
    return float(value)


def _view(views: object) -> View | None:
    """Orbit-like views (Orbit, XYOrbit, ThirdPersonFollower) and TopDownOrtho as a camera
    position and target; other view classes keep viser's own camera."""
    if not isinstance(views, dict) or not isinstance(views.get('Current'), dict):
        return None
    current: dict[object, object] = views['Current']
    kind = str(current.get('Class', '')).rpartition('/')[2]
    if kind == 'TopDownOrtho':
        x, y = _number(current, 'X', 0.0), _number(current, 'Y', 0.0)
        scale = _number(current, 'Scale', 10.0)
        height = max(1.0, 800.0 / max(scale, 1e-3))
        return View((x - 1e-3, y, height), (x, y, 0.0))
    if kind not in ('Orbit', 'XYOrbit', 'ThirdPersonFollower', 'FPS'):
        return None
    focal = current.get('Focal Point', {})
    if not isinstance(focal, dict):
        focal = {}
    fx, fy, fz = (_number(focal, k, 0.0) for k in ('X', 'Y', 'Z'))
    distance = _number(current, 'Distance', 10.0)
    pitch, yaw = _number(current, 'Pitch', 0.785), _number(current, 'Yaw', 0.785)
    position = (
        fx + distance * math.cos(pitch) * math.cos(yaw),
        fy + distance * math.cos(pitch) * math.sin(yaw),
        fz + distance * math.sin(pitch),
    )
    return View(position, (fx, fy, fz))
