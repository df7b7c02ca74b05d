"""The viewer: a viser server whose scene is the fixed frame, a node that listens, and a
render loop between them.

The node's callbacks only store (each display keeps its newest message); the render loop,
on its own thread, draws what is new and places it by TF, so a slow or stalled browser slows
only what viser sends it (viser keeps the newest message per scene node for each client),
never the graph. Zero configuration: every topic of a type a display draws gets that
display as it appears, and the fixed frame is the TF tree's root.
"""

from __future__ import annotations

import dataclasses
import math
import socket
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from ros2lite.bundled.rviz2.clients import Clouds
from ros2lite.bundled.rviz2.config import KINDS, ROBOT_DESCRIPTION, TOPIC_KINDS, Config, DisplaySpec
from ros2lite.bundled.rviz2.convert import Pose, ground_hit, wxyz, yaw_quaternion
from ros2lite.bundled.rviz2.displays import CLASSES, Shown
from ros2lite.bundled.rviz2.markers import MarkerDisplay
from ros2lite.bundled.rviz2.robot import RobotModelDisplay

if TYPE_CHECKING:
    import viser

    from ros2lite.node import Node
    from ros2lite.publisher import Publisher
    from ros2lite.tf2 import Buffer
    from ros2lite.type_support import Msg

RENDER_HZ = 20.0
GRAPH_PERIOD = 1.0  # how often the graph is read for new topics (zero configuration)
TREE_PERIOD = 1.0  # how often the frame tree panel and TF axes are redrawn
DEFAULT_FRAME = 'map'  # RViz's, when nothing says otherwise and no TF has arrived

TOOLS = {
    '2D Pose Estimate': ('/initialpose', 'geometry_msgs/msg/PoseWithCovarianceStamped'),
    '2D Goal Pose': ('/goal_pose', 'geometry_msgs/msg/PoseStamped'),
    'Publish Point': ('/clicked_point', 'geometry_msgs/msg/PointStamped'),
}


@dataclasses.dataclass
class Settings:
    host: str = '127.0.0.1'
    port: int = 8080
    fixed_frame: str = ''
    point_budget: int = 200_000
    image_width: int = 640


def frame_tree(parents: dict[str, str]) -> list[tuple[int, str]]:
    """(depth, frame) rows of the TF tree, roots first, children sorted."""
    children: dict[str, list[str]] = {}
    for child, parent in parents.items():
        children.setdefault(parent, []).append(child)
    roots = sorted(
        {p for p in parents.values() if p not in parents}
        | {f for f in parents if f not in parents.values() and f not in parents}
    )
    rows: list[tuple[int, str]] = []
    seen: set[str] = set()

    def walk(frame: str, depth: int) -> None:
        if frame in seen:
            return
        seen.add(frame)
        rows.append((depth, frame))
        for c in sorted(children.get(frame, [])):
            walk(c, depth + 1)

    for r in roots:
        walk(r, 0)
    return rows


def tree_root(parents: dict[str, str]) -> str:
    """The root of the largest TF tree (the fixed frame zero configuration picks)."""
    rows = frame_tree(parents)
    best, best_size, current, size = '', -1, '', 0
    for depth, frame in [*rows, (0, '')]:
        if depth == 0:
            if current and size > best_size:
                best, best_size = current, size
            current, size = frame, 0
        size += 1
    return best


def make(ctx: Viewer, spec: DisplaySpec, type_name: str) -> Shown:
    """The display of `spec`'s kind for messages of `type_name`."""
    from ros2lite.interfaces import get_interface

    cls = get_interface(type_name)
    if spec.kind in ('Marker', 'MarkerArray'):
        return MarkerDisplay(ctx, spec, cls)
    if spec.kind == 'RobotModel':
        return RobotModelDisplay(ctx, spec, cls)
    return CLASSES[spec.kind](ctx, spec, cls)


def page_url(host: str, port: int) -> str:
    """The address to open: a server on every interface is named by this machine's name (an
    address of 0.0.0.0 opens nothing elsewhere), an IPv6 address in brackets."""
    if host in ('0.0.0.0', '::', ''):
        host = socket.gethostname()
    elif ':' in host:
        host = f'[{host}]'
    return f'http://{host}:{port}'


class Viewer:
    """The scene, its displays and the tools, served at `settings.host:port`."""

    def __init__(self, node: Node, buffer: Buffer, settings: Settings, config: Config) -> None:
        import viser

        self.node = node
        self.buffer = buffer
        self.settings = settings
        self.image_width = settings.image_width
        self.config = config
        self.auto = not config.displays
        self.fixed_frame = settings.fixed_frame or config.fixed_frame
        self._user_frame = bool(self.fixed_frame)
        self.displays: dict[str, Shown] = {}
        self._messages: dict[str, str] = {}
        self._lock = threading.Lock()
        self._first_frame = ''
        self._tf_handles: dict[str, tuple[viser.FrameHandle, viser.LabelHandle]] = {}
        self._tree_at = 0.0
        self._tool: str | None = None
        self._clicks: list[tuple[float, float]] = []
        self._publishers: dict[str, Publisher[Msg]] = {}
        self.published = 0
        self.server = viser.ViserServer(host=settings.host, port=settings.port, verbose=False)
        self.server.gui.configure_theme(control_width='medium')
        if config.view is not None:
            self.server.initial_camera.position = config.view.position
            self.server.initial_camera.look_at = config.view.look_at
        else:
            self.server.initial_camera.position = (-6.0, -6.0, 6.0)
            self.server.initial_camera.look_at = (0.0, 0.0, 0.0)
        self._build_gui()
        # each page's own point budget, its box in Global Options
        self.clouds = Clouds(self.server, settings.point_budget, self._global_folder)
        specs = config.displays or (DisplaySpec('Grid'), DisplaySpec('TF'))
        self._grid: viser.GridHandle | None = None
        self._tf_shown = False
        for spec in specs:
            self.add(spec, '')
        if self.auto:
            # on the executor's thread: a subscription made while the executor spins on
            # another thread can be seen by it half-built (its source not yet set)
            node.create_timer(GRAPH_PERIOD, self.discover)

    @property
    def url(self) -> str:
        return page_url(self.server.get_host(), self.server.get_port())

    # -- the panels ------------------------------------------------------------------------
    def _build_gui(self) -> None:
        gui = self.server.gui
        with gui.add_folder('Global Options') as self._global_folder:
            self._frame_box = gui.add_text('Fixed Frame', initial_value=self.fixed_frame)
            self._frame_box.on_update(lambda _: self._set_fixed(self._frame_box.value))
        with gui.add_folder('Tools'):
            for label in TOOLS:
                gui.add_button(label).on_click(self._arming(label))
            self._tool_text = gui.add_markdown('')
        self._displays_folder = gui.add_folder('Displays')
        with gui.add_folder('TF frames', expand_by_default=False):
            self._tree_text = gui.add_markdown('*no TF received*')
        self._status_text = gui.add_markdown('')

    def _set_fixed(self, frame: str) -> None:
        frame = frame.strip().lstrip('/')
        if frame != self.fixed_frame:  # typed by the user, not set by _choose_fixed
            self.fixed_frame = frame
            self._user_frame = bool(frame)

    def status(self, display: Shown, text: str) -> None:
        self._messages[display.spec.name or display.name] = text

    # -- displays --------------------------------------------------------------------------
    def add(self, spec: DisplaySpec, type_name: str) -> None:
        """A display for `spec` (a topic's type chosen from the graph, or the kind's first)."""
        key = f'{spec.kind}:{spec.topic}'
        if key in self.displays or (spec.kind in ('Grid', 'TF') and self._has(spec.kind)):
            return
        with self._displays_folder:
            box = self.server.gui.add_checkbox(
                f'{spec.kind} {spec.topic}'.strip(), initial_value=spec.enabled
            )
        if spec.kind == 'Grid':
            self._grid = self.server.scene.add_grid(
                '/Grid',
                10.0,
                10.0,
                cell_size=1.0,
                section_size=1.0,
                cell_color=(160, 160, 164),
                section_color=(160, 160, 164),
                visible=spec.enabled,
            )
            box.on_update(lambda _: self._show_grid(box.value))
            self.displays[key] = Shown(spec)
            return
        if spec.kind == 'TF':
            self._tf_shown = spec.enabled
            box.on_update(lambda _: self._show_tf(box.value))
            self.displays[key] = Shown(spec)
            return
        display = make(self, spec, type_name or KINDS[spec.kind][0])
        display.subscribe()
        box.on_update(lambda _: display.set_enabled(box.value))
        with self._lock:
            self.displays[key] = display

    def _has(self, kind: str) -> bool:
        return any(d.spec.kind == kind for d in self.displays.values())

    def _show_grid(self, shown: bool) -> None:
        if self._grid is not None:
            self._grid.visible = shown

    def _show_tf(self, shown: bool) -> None:
        self._tf_shown = shown
        for axes, label in self._tf_handles.values():
            axes.visible = label.visible = shown

    def discover(self) -> None:
        """Zero configuration: a display for each new topic of a drawable type."""
        for topic, types in self.node.get_topic_names_and_types():
            for type_name in types:
                kind = TOPIC_KINDS.get(type_name)
                if topic == ROBOT_DESCRIPTION and type_name == 'std_msgs/msg/String':
                    kind = 'RobotModel'
                if kind is not None:
                    self.add(DisplaySpec(kind, topic, True, f'{kind} {topic}'), type_name)
                    break

    # -- where things are ------------------------------------------------------------------
    def parents(self) -> dict[str, str]:
        """Each frame's parent (a frame whose data was cleared has none: left out)."""
        return {c: p for c, p in self.buffer.frame_parents().items() if p != 'NO_PARENT'}

    def place(self, frame: str, ns: int) -> Pose | None:
        """Where `frame` is in the fixed frame at `ns` (the latest when TF has no data then)."""
        from ros2lite.tf2 import TransformException

        frame = frame.lstrip('/')
        if not self._first_frame and frame:
            self._first_frame = frame
        fixed = self.fixed_frame or self._first_frame
        if frame == fixed or not frame:
            return ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
        for at in (ns, 0) if ns else (0,):
            try:
                transform, _ = self.buffer.lookup(fixed, frame, at)
                return transform
            except TransformException:
                continue
        return None

    def _choose_fixed(self, parents: dict[str, str]) -> None:
        """The TF tree's root, unless the user (option, file or the box) named a frame."""
        if self._user_frame:
            return
        root = tree_root(parents)
        if root and root != self.fixed_frame:
            self.fixed_frame = root
            self._frame_box.value = root  # type: ignore[misc]  # viser's setter, untyped

    def _draw_tf(self, parents: dict[str, str]) -> None:
        rows = frame_tree(parents)
        self._tree_text.content = (
            '\n'.join(
                f'{"&nbsp;" * 4 * depth}{"**" + f + "**" if f == self.fixed_frame else f}  '
                for depth, f in rows
            )
            or '*no TF received*'
        )
        for _, frame in rows:
            pose = self.place(frame, 0)
            handles = self._tf_handles.get(frame)
            if handles is None:
                safe = frame.replace('/', '.')
                axes = self.server.scene.add_frame(
                    f'/TF/{safe}', axes_length=0.3, axes_radius=0.015, visible=False
                )
                label = self.server.scene.add_label(f'/TF/{safe}/name', frame, visible=False)
                handles = self._tf_handles[frame] = (axes, label)
            axes, label = handles
            shown = self._tf_shown and pose is not None
            axes.visible = label.visible = shown
            if pose is not None:
                axes.position, axes.wxyz = pose[0], wxyz(pose[1])

    # -- the loop --------------------------------------------------------------------------
    def tick(self) -> None:
        """One pass of the render loop."""
        now = time.monotonic()
        if now - self._tree_at >= TREE_PERIOD:
            self._tree_at = now
            parents = self.parents()
            self._choose_fixed(parents)
            self._draw_tf(parents)
            self._show_status()
        with self._lock:
            displays = list(self.displays.values())
        self.clouds.begin()
        with self.server.atomic():
            for d in displays:
                if d.spec.kind not in ('Grid', 'TF'):
                    d.render()

    def _show_status(self) -> None:
        """Each display's count of messages received (RViz's status line), its problems,
        and the fixed frame in use."""
        with self._lock:
            counts = [
                (d.spec.name or d.name, d.received) for d in self.displays.values() if d.spec.topic
            ]
        lines = [f'{name}: {n} messages' for name, n in counts]
        lines += [f'{k}: {v}' for k, v in sorted(self._messages.items())]
        lines.append(f'fixed frame: {self.fixed_frame or self._first_frame or "?"}')
        self._status_text.content = '  \n'.join(lines)
        self._messages.clear()

    def run(self, ok: Callable[[], bool]) -> None:
        """Render until `ok()` is False."""
        period = 1.0 / RENDER_HZ
        while ok():
            start = time.monotonic()
            self.tick()
            time.sleep(max(0.0, period - (time.monotonic() - start)))

    def close(self) -> None:
        for d in self.displays.values():
            d.close()
        self.server.stop()

    # -- the tools -------------------------------------------------------------------------
    def _arming(self, tool: str) -> Callable[[object], None]:
        return lambda _: self.arm(tool)

    def arm(self, tool: str) -> None:
        """The tool clicked: the next click on the ground (and a second for the heading)."""
        self._tool = tool
        self._clicks = []
        self._tool_text.content = f'**{tool}**: click the ground' + (
            ', then click where it faces' if tool != 'Publish Point' else ''
        )
        self.server.scene.remove_click_callback()
        self.server.scene.on_click()(self._on_click)

    def _on_click(self, event: viser.SceneClickEvent) -> None:
        hit = ground_hit(event.ray_origin, event.ray_direction)
        if self._tool is None or hit is None:
            return
        self._clicks.append(hit)
        if self._tool != 'Publish Point' and len(self._clicks) < 2:
            self._tool_text.content = f'**{self._tool}**: now click where it faces'
            return
        tool, clicks = self._tool, self._clicks
        self._tool, self._clicks = None, []
        self.server.scene.remove_click_callback()
        self.publish(tool, clicks)

    def publish(self, tool: str, clicks: list[tuple[float, float]]) -> None:
        """What the tool sends, in the fixed frame: a point, or a pose at the first click
        facing the second."""
        from ros2lite.interfaces import get_interface

        topic, type_name = TOOLS[tool]
        pub = self._publishers.get(topic)
        if pub is None:
            pub = self._publishers[topic] = self.node.create_publisher(type_name, topic, 10)
        msg = get_interface(type_name)()
        msg.header.frame_id = self.fixed_frame or self._first_frame or DEFAULT_FRAME
        msg.header.stamp = self.node.get_clock().now().to_msg()
        (x, y) = clicks[0]
        if tool == 'Publish Point':
            msg.point.x, msg.point.y = x, y
        else:
            x2, y2 = clicks[-1]
            yaw = math.atan2(y2 - y, x2 - x) if (x2, y2) != (x, y) else 0.0
            pose = msg.pose.pose if tool == '2D Pose Estimate' else msg.pose
            pose.position.x, pose.position.y = x, y
            q = yaw_quaternion(yaw)
            pose.orientation.z, pose.orientation.w = q[2], q[3]
            if tool == '2D Pose Estimate':
                # RViz's covariance: 0.5 m in x and y, pi/12 in yaw
                cov = [0.0] * 36
                cov[0] = cov[7] = 0.25
                cov[35] = 0.06853891909122467
                msg.pose.covariance = cov
        pub.publish(msg)
        self.published += 1
        self._tool_text.content = f'sent on {topic} at ({x:.2f}, {y:.2f})'
