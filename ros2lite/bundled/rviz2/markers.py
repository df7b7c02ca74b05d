"""Marker and MarkerArray displays: every marker type RViz draws, kept by (ns, id) so the
newest of each wins, with ADD/MODIFY, DELETE, DELETEALL and lifetimes.

The callback only files the marker under its key (or forgets keys); the render loop draws
what changed and places each marker by TF (at its stamp, or the latest for frame_locked)."""

from __future__ import annotations

import time
from typing import TYPE_CHECKING, Literal

import numpy as np

from ros2lite.bundled.rviz2.convert import ConvertError, pose_of, stamp_ns, then, wxyz
from ros2lite.bundled.rviz2.displays import Context, Display, arrows
from ros2lite.msgs.std_msgs.msg import ColorRGBA
from ros2lite.msgs.visualization_msgs.msg import Marker, MarkerArray

if TYPE_CHECKING:
    from pathlib import Path

    import trimesh
    import viser

    from ros2lite.bundled.rviz2.config import DisplaySpec

ARROW, CUBE, SPHERE, CYLINDER, LINE_STRIP, LINE_LIST = 0, 1, 2, 3, 4, 5
CUBE_LIST, SPHERE_LIST, POINTS, TEXT_VIEW_FACING, MESH_RESOURCE, TRIANGLE_LIST = 6, 7, 8, 9, 10, 11
ADD, DELETE, DELETEALL = 0, 2, 3
MAX_MARKERS = 10_000  # a bound on what one display keeps: a runaway publisher cannot grow it

Key = tuple[str, int]


def _rgb(c: ColorRGBA) -> tuple[int, int, int]:
    return (
        round(max(0.0, min(1.0, c.r)) * 255),
        round(max(0.0, min(1.0, c.g)) * 255),
        round(max(0.0, min(1.0, c.b)) * 255),
    )


def _points(marker: Marker) -> np.ndarray:
    return np.array(
        [(p.x, p.y, p.z) for p in marker.points],
        np.float32,
    ).reshape(-1, 3)


def _length(ends: np.ndarray) -> float:
    return float(np.linalg.norm(ends[0, 1] - ends[0, 0]))


def _colours(marker: Marker, n: int) -> np.ndarray:
    """Per-point colours when the marker gives one for each point, else its one colour."""
    colours = marker.colors
    if len(colours) == n and n:
        return np.array([_rgb(c) for c in colours], np.uint8)
    return np.tile(np.array(_rgb(marker.color), np.uint8), (n, 1))


class MarkerDisplay(Display[Marker | MarkerArray]):
    """visualization_msgs/Marker or MarkerArray on one topic."""

    def __init__(
        self, ctx: Context, spec: DisplaySpec, msg_class: type[Marker | MarkerArray]
    ) -> None:
        super().__init__(ctx, spec, msg_class)
        self.markers: dict[Key, tuple[Marker, float | None]] = {}
        self.changed: set[Key] = set()
        self.gone: set[Key] = set()
        self.handles: dict[Key, viser.FrameHandle] = {}
        # each marker's drawing, under its frame: replaced on change, the frame kept
        self.shapes: dict[Key, viser.SceneNodeHandle] = {}

    def store(self, msg: Marker | MarkerArray) -> None:
        now = time.monotonic()
        items = msg.markers if isinstance(msg, MarkerArray) else [msg]
        with self._lock:
            self.received += 1
            for m in items:
                self._file(m, now)

    def _file(self, m: Marker, now: float) -> None:
        action = int(m.action)
        if action == DELETEALL:
            self.gone.update(self.markers)
            self.markers.clear()
            self.changed.clear()
            return
        key = (str(m.ns), int(m.id))
        if action == DELETE:
            if self.markers.pop(key, None) is not None:
                self.gone.add(key)
            self.changed.discard(key)
            return
        if key not in self.markers and len(self.markers) >= MAX_MARKERS:
            return
        life = m.lifetime
        seconds = life.sec + life.nanosec / 1e9
        self.markers[key] = (m, now + seconds if seconds > 0 else None)
        self.changed.add(key)
        self.gone.discard(key)

    def render(self) -> None:
        now = time.monotonic()
        with self._lock:
            for key, (_, until) in list(self.markers.items()):
                if until is not None and until <= now:
                    del self.markers[key]
                    self.gone.add(key)
                    self.changed.discard(key)
            gone, self.gone = self.gone, set()
            changed, self.changed = self.changed, set()
            current = dict(self.markers)
        for key in gone:
            self.shapes.pop(key, None)
            handle = self.handles.pop(key, None)
            if handle is not None:
                handle.remove()
        for key in changed:
            try:
                self._draw_one(key, current[key][0])
            except ConvertError as e:
                self.ctx.status(self, str(e))
        if changed:
            self.drawn += 1
        for key, (marker, _) in current.items():
            self._place(key, marker)

    def _name(self, key: Key) -> str:
        ns = key[0].replace('/', '.') or '_'
        return f'{self.name}/{ns}:{key[1]}'

    def _place(self, key: Key, marker: Marker) -> None:
        handle = self.handles.get(key)
        if handle is None:
            return
        header = marker.header
        ns = 0 if marker.frame_locked else stamp_ns(header)
        where = self.ctx.place(header.frame_id, ns)
        if where is None:
            handle.visible = False
            self.ctx.status(self, f'no transform from {header.frame_id!r} to the fixed frame')
            return
        pose = then(where, pose_of(marker.pose))
        handle.visible = self.enabled
        handle.position = pose[0]
        handle.wxyz = wxyz(pose[1])

    def _draw_one(self, key: Key, m: Marker) -> None:
        scene = self.ctx.server.scene
        name = self._name(key)
        # the frame stays (made anew, a page that joins later saw it at the origin: viser's
        # replay put the old frame's pose before the new frame); only the shape is replaced,
        # so a marker whose type changed leaves nothing of its old one
        old = self.shapes.pop(key, None)
        if old is not None:
            old.remove()
        if key not in self.handles:
            self.handles[key] = scene.add_frame(name, show_axes=False, visible=False)
        kind = int(m.type)
        s = m.scale
        sx, sy, sz = float(s.x), float(s.y), float(s.z)
        colour = _rgb(m.color)
        alpha = float(m.color.a)
        opacity = alpha if alpha < 1.0 else None
        g = f'{name}/shape'
        if kind == CUBE:
            self.shapes[key] = scene.add_box(g, colour, (sx, sy, sz), opacity=opacity)
        elif kind == SPHERE:
            self.shapes[key] = scene.add_icosphere(
                g, 0.5, colour, scale=(sx, sy, sz), opacity=opacity
            )
        elif kind == CYLINDER:
            # viser's cylinder stands on z, as RViz's does; diameter x/y, height z
            self.shapes[key] = scene.add_cylinder(
                g, 0.5, 1.0, colour, scale=(sx, sy, sz), opacity=opacity
            )
        elif kind == ARROW:
            pts = _points(m)
            if len(pts) >= 2:
                ends = pts[:2].reshape(1, 2, 3)
                self.shapes[key] = scene.add_arrows(
                    g,
                    ends,
                    colour,
                    shaft_radius=sx / 2,
                    head_radius=sy / 2,
                    head_length=sz
                    if sz > 0
                    else 0.23 * float(np.linalg.norm(ends[0, 1] - ends[0, 0])),
                )
            else:
                ends = arrows([((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))], sx)
                self.shapes[key] = scene.add_arrows(
                    g, ends, colour, shaft_radius=sy / 2, head_radius=sz / 2, head_length=0.23 * sx
                )
        elif kind in (LINE_STRIP, LINE_LIST):
            pts = _points(m)
            segs = (
                np.stack([pts[:-1], pts[1:]], axis=1)
                if kind == LINE_STRIP
                else pts[: len(pts) // 2 * 2].reshape(-1, 2, 3)
            )
            if len(segs):
                colours = _colours(m, len(pts))
                seg_colours = colours[:-1] if kind == LINE_STRIP else colours[0::2]
                self.shapes[key] = scene.add_line_segments(
                    g, segs, seg_colours[:, None, :].repeat(2, axis=1), thickness=max(sx, 1e-3)
                )
        elif kind in (CUBE_LIST, SPHERE_LIST, POINTS):
            pts = _points(m)
            if len(pts):
                shape: Literal['square', 'circle'] = (
                    'square' if kind in (CUBE_LIST, POINTS) else 'circle'
                )
                self.shapes[key] = scene.add_point_cloud(
                    g,
                    pts,
                    _colours(m, len(pts)),
                    point_size=max(sx, 1e-3),
                    point_shape=shape,
                    point_shading='flat',
                )
        elif kind == TEXT_VIEW_FACING:
            self.shapes[key] = scene.add_label(
                g,
                str(m.text),
                font_size_mode='scene',
                font_scene_height=max(sz, 0.01),
                anchor='center-center',
            )
        elif kind == TRIANGLE_LIST:
            pts = _points(m)
            n = len(pts) // 3 * 3
            if n:
                self.shapes[key] = scene.add_mesh_simple(
                    g,
                    pts[:n] * (sx, sy, sz),
                    np.arange(n, dtype=np.uint32).reshape(-1, 3),
                    color=colour,
                    opacity=opacity,
                    side='double',
                )
        elif kind == MESH_RESOURCE:
            mesh = load_mesh(str(m.mesh_resource))
            if not m.mesh_use_embedded_materials:
                mesh.visual = flat_visual(mesh, colour)
            self.shapes[key] = scene.add_mesh_trimesh(g, mesh, scale=(sx, sy, sz))
        else:
            raise ConvertError(f'marker type {kind} is not one RViz draws')

    def set_enabled(self, enabled: bool) -> None:
        self.enabled = enabled
        for handle in self.handles.values():
            handle.visible = enabled

    def close(self) -> None:
        super().close()
        for handle in self.handles.values():
            handle.remove()
        self.handles.clear()
        self.shapes.clear()


def load_mesh(uri: str) -> trimesh.Trimesh:
    """A mesh file (STL, DAE, OBJ) by `package://` or `file://` URI, through the package
    index (only files of package share folders), as one trimesh."""
    import trimesh

    path = resolve(uri)
    try:
        loaded = trimesh.load(str(path), force='mesh')
    except Exception as e:  # trimesh's loaders raise what their formats' readers raise
        raise ConvertError(f'cannot load mesh {uri}: {e}') from None
    if not isinstance(loaded, trimesh.Trimesh):
        raise ConvertError(f'mesh {uri} holds no triangles')
    return loaded


def resolve(uri: str) -> Path:
    """`package://` and `file://` URIs to a file inside a package's share folder (nothing
    else of the filesystem), through ros2lite.urdf."""
    from ros2lite.urdf import UrdfError, resolve_resource

    try:
        return resolve_resource(uri)
    except (UrdfError, OSError) as e:
        raise ConvertError(f'cannot resolve mesh {uri}: {e}') from None


def flat_visual(mesh: trimesh.Trimesh, colour: tuple[int, int, int]) -> trimesh.visual.ColorVisuals:
    import trimesh

    return trimesh.visual.ColorVisuals(mesh, face_colors=(*colour, 255))
