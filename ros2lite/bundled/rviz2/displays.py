"""The displays that draw one topic each: LaserScan, PointCloud2, Odometry, Path, Pose,
PoseArray, Map, Image.

A subscription callback only keeps the newest message (newest wins: nothing queues behind a
slow browser); the render loop draws it under a frame node placed by TF at the message's
stamp. Scans and clouds are drawn per browser, each decimated to that page's point budget
(clients.py).
"""

from __future__ import annotations

import collections
import io
import threading
from collections.abc import Callable
from typing import TYPE_CHECKING, Generic, Protocol

import numpy as np

from ros2lite.bundled.rviz2.clients import Clouds
from ros2lite.bundled.rviz2.config import DisplaySpec
from ros2lite.bundled.rviz2.convert import (
    IDENTITY,
    Bytes,
    ConvertError,
    Floats,
    Pose,
    cloud_points,
    grid_image,
    image_rgb,
    pose_of,
    scaled,
    scan_points,
    stamp_ns,
    then,
    wxyz,
)
from ros2lite.msgs.geometry_msgs.msg import PoseArray, PoseStamped, PoseWithCovarianceStamped
from ros2lite.msgs.nav_msgs.msg import OccupancyGrid, Odometry, Path
from ros2lite.msgs.sensor_msgs.msg import CompressedImage, Image, LaserScan, PointCloud2
from ros2lite.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from ros2lite.type_support import MsgT

if TYPE_CHECKING:
    import viser

    from ros2lite.node import Node
    from ros2lite.subscription import Subscription

SCAN_COLOUR = (255, 0, 0)  # RViz's LaserScan default is the intensity rainbow; red reads best
ODOMETRY_KEEP = 100  # RViz's Odometry display keeps 100 arrows
POSE_COLOUR = (255, 25, 0)  # RViz's Pose arrow


class Context(Protocol):
    """What displays draw with (the viewer gives it)."""

    server: viser.ViserServer
    node: Node
    clouds: Clouds
    image_width: int

    def place(self, frame: str, ns: int) -> Pose | None:
        """The pose of `frame` in the fixed frame at `ns` (0: the latest), or None when TF
        cannot say."""
        ...

    def status(self, display: Shown, text: str) -> None: ...


class Shown:
    """What the viewer holds of a display, whatever it draws (Grid and TF are just this)."""

    def __init__(self, spec: DisplaySpec) -> None:
        self.spec = spec
        self.name = node_name(spec)
        self.enabled = spec.enabled
        self.received = 0
        self.drawn = 0
        self.last_stamp_ns = 0

    def subscribe(self) -> None:
        pass

    def render(self) -> None:
        pass

    def set_enabled(self, enabled: bool) -> None:
        self.enabled = enabled

    def close(self) -> None:
        pass


def node_name(spec: DisplaySpec) -> str:
    """A display's scene-tree name: one level, so its parts are its children."""
    return f'/{spec.kind}{spec.topic.replace("/", ".") if spec.topic else ""}'


def qos_for(kind: str) -> QoSProfile:
    """Sensor streams best effort (matches every publisher, never backs one up); maps and
    the robot description transient local (published once, latched)."""
    if kind in ('Map', 'RobotModel'):
        return QoSProfile(
            depth=1,
            reliability=ReliabilityPolicy.RELIABLE,
            durability=DurabilityPolicy.TRANSIENT_LOCAL,
        )
    if kind in ('Marker', 'MarkerArray'):
        return QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE)
    return QoSProfile(depth=1, reliability=ReliabilityPolicy.BEST_EFFORT)


class Display(Shown, Generic[MsgT]):
    """One topic's display: newest message kept, drawn by `render`."""

    def __init__(self, ctx: Context, spec: DisplaySpec, msg_class: type[MsgT]) -> None:
        super().__init__(spec)
        self.ctx = ctx
        self.msg_class = msg_class
        self._lock = threading.Lock()
        self._latest: MsgT | None = None
        self._fresh = False
        self._root: viser.FrameHandle | None = None
        self._subscription: Subscription[MsgT] | None = None

    # -- the graph side: a callback that only stores -----------------------------------
    def subscribe(self) -> None:
        self._subscription = self.ctx.node.create_subscription(
            self.msg_class, self.spec.topic, self.store, qos_for(self.spec.kind)
        )

    def store(self, msg: MsgT) -> None:
        """The subscription callback: keep the newest, drop the one before."""
        with self._lock:
            self._latest = msg
            self._fresh = True
            self.received += 1

    def take(self) -> tuple[MsgT | None, bool]:
        """The newest message and whether it is new since the last call."""
        with self._lock:
            fresh, self._fresh = self._fresh, False
            return self._latest, fresh

    # -- the browser side ---------------------------------------------------------------
    def root(self) -> viser.FrameHandle:
        if self._root is None:
            self._root = self.ctx.server.scene.add_frame(self.name, show_axes=False)
        return self._root

    def render(self) -> None:
        """Draw the newest message if it is new, and place it by TF."""
        msg, fresh = self.take()
        if msg is None:
            return
        if fresh and self.enabled:
            try:
                self.draw(msg)
            except ConvertError as e:
                self.ctx.status(self, str(e))
                return
            self.drawn += 1
            header = getattr(msg, 'header', None)
            if header is not None:
                self.last_stamp_ns = stamp_ns(header)
        self.position(msg)

    def position(self, msg: MsgT) -> None:
        """Put the display's frame where TF says the message's frame was at its stamp."""
        header = getattr(msg, 'header', None)
        root = self.root()
        if header is None:
            return
        pose = self.ctx.place(header.frame_id, stamp_ns(header))
        if pose is None:
            root.visible = False
            self.ctx.status(self, f'no transform from {header.frame_id!r} to the fixed frame')
            return
        root.visible = self.enabled
        root.position = pose[0]
        root.wxyz = wxyz(pose[1])

    def set_enabled(self, enabled: bool) -> None:
        self.enabled = enabled
        if self._root is not None:
            self._root.visible = enabled
        with self._lock:
            self._fresh = self._latest is not None  # redraw what arrived while hidden

    def draw(self, msg: MsgT) -> None:
        raise NotImplementedError

    def close(self) -> None:
        if self._subscription is not None:
            self.ctx.node.destroy_subscription(self._subscription)
        if self._root is not None:
            self._root.remove()


class CloudDisplay(Display[MsgT]):
    """Points sent to each browser apart, decimated to its budget, under the display's frame
    (the shared scene's node, placed by TF): the newest message's points are kept, so a
    page that comes or changes its budget is sent them at the next pass."""

    point_size = 0.03

    def __init__(self, ctx: Context, spec: DisplaySpec, msg_class: type[MsgT]) -> None:
        super().__init__(ctx, spec, msg_class)
        self._cloud: tuple[Floats, Bytes] | None = None
        self.label = spec.name or f'{spec.kind} {spec.topic}'

    def points(self, msg: MsgT) -> tuple[Floats, Bytes]:
        raise NotImplementedError

    def draw(self, msg: MsgT) -> None:
        self._cloud = self.points(msg)
        self._send(everyone=True)

    def render(self) -> None:
        drawn = self.drawn
        super().render()
        if (
            self.drawn == drawn
            and self.enabled
            and self._cloud is not None
            and self.ctx.clouds.redraw()
        ):
            self._send(everyone=False)  # only to the pages that came or changed budget

    def _send(self, *, everyone: bool) -> None:
        if self._cloud is not None:
            self.root()  # the shared frame the pages' points hang from
            points, colours = self._cloud
            name = f'{self.name}/points'
            self.ctx.clouds.send(
                name, self.label, points, colours, self.point_size, everyone=everyone
            )

    def close(self) -> None:
        self.ctx.clouds.remove(f'{self.name}/points', self.label)
        super().close()


class LaserScanDisplay(CloudDisplay[LaserScan]):
    point_size = 0.05

    def points(self, msg: LaserScan) -> tuple[Floats, Bytes]:
        points = scan_points(msg)
        return points, np.tile(np.array(SCAN_COLOUR, np.uint8), (len(points), 1))


class PointCloud2Display(CloudDisplay[PointCloud2]):
    def points(self, msg: PointCloud2) -> tuple[Floats, Bytes]:
        return cloud_points(msg)


def arrows(poses: list[Pose], length: float) -> np.ndarray:
    """Arrow start/end pairs along each pose's x axis."""
    from ros2lite.tf2.math import rotate

    out = np.zeros((len(poses), 2, 3), np.float32)
    for i, (p, q) in enumerate(poses):
        d = rotate(q, (length, 0.0, 0.0))
        out[i, 0] = p
        out[i, 1] = (p[0] + d[0], p[1] + d[1], p[2] + d[2])
    return out


class PoseDisplay(Display[PoseStamped | PoseWithCovarianceStamped]):
    """PoseStamped and PoseWithCovarianceStamped: one arrow."""

    def draw(self, msg: PoseStamped | PoseWithCovarianceStamped) -> None:
        pose = msg.pose.pose if isinstance(msg, PoseWithCovarianceStamped) else msg.pose
        self.ctx.server.scene.add_arrows(
            f'{self.name}/arrow',
            arrows([pose_of(pose)], 1.0),
            POSE_COLOUR,
            shaft_radius=0.05,
            head_radius=0.1,
            head_length=0.3,
        )


class PoseArrayDisplay(Display[PoseArray]):
    def draw(self, msg: PoseArray) -> None:
        poses = [pose_of(p) for p in msg.poses]
        self.ctx.server.scene.add_arrows(
            f'{self.name}/arrows',
            arrows(poses, 0.3),
            POSE_COLOUR,
            shaft_radius=0.01,
            head_radius=0.03,
            head_length=0.08,
        )


class PathDisplay(Display[Path]):
    def draw(self, msg: Path) -> None:
        pts = np.array(
            [pose_of(p.pose)[0] for p in msg.poses],
            np.float32,
        ).reshape(-1, 3)
        if len(pts) < 2:
            return
        segments = np.stack([pts[:-1], pts[1:]], axis=1)
        self.ctx.server.scene.add_line_segments(
            f'{self.name}/line', segments, (25, 255, 0), thickness=0.03
        )


class OdometryDisplay(Display[Odometry]):
    """The newest odometry poses, as arrows kept in the fixed frame (a trail)."""

    def __init__(self, ctx: Context, spec: DisplaySpec, msg_class: type[Odometry]) -> None:
        super().__init__(ctx, spec, msg_class)
        self.trail: collections.deque[Pose] = collections.deque(maxlen=ODOMETRY_KEEP)

    def draw(self, msg: Odometry) -> None:
        header = msg.header
        where = self.ctx.place(header.frame_id, stamp_ns(header))
        if where is None:
            self.ctx.status(self, f'no transform from {header.frame_id!r} to the fixed frame')
            return
        self.trail.append(then(where, pose_of(msg.pose.pose)))
        self.ctx.server.scene.add_arrows(
            f'{self.name}/arrows',
            arrows(list(self.trail), 1.0),
            POSE_COLOUR,
            shaft_radius=0.02,
            head_radius=0.06,
            head_length=0.2,
        )

    def position(self, msg: MsgT) -> None:
        root = self.root()  # the trail is drawn in the fixed frame already
        root.visible = self.enabled
        root.position, root.wxyz = IDENTITY[0], (1.0, 0.0, 0.0, 0.0)


class MapDisplay(Display[OccupancyGrid]):
    """An OccupancyGrid as a flat picture at its origin, cell (0, 0) at the origin's corner."""

    def draw(self, msg: OccupancyGrid) -> None:
        info = msg.info
        img = grid_image(msg)[::-1]  # the image's top row is the grid's last row (largest y)
        w, h = int(info.width) * info.resolution, int(info.height) * info.resolution
        origin = pose_of(info.origin)
        centre = then(origin, ((w / 2, h / 2, 0.0), (0.0, 0.0, 0.0, 1.0)))
        self.ctx.server.scene.add_image(
            f'{self.name}/map',
            img,
            w,
            h,
            format='png',
            position=centre[0],
            wxyz=wxyz(centre[1]),
            cast_shadow=False,
            receive_shadow=False,
        )


class ImageDisplay(Display[Image | CompressedImage]):
    """A camera image in a panel, re-encoded as JPEG and shrunk for the link."""

    def __init__(
        self, ctx: Context, spec: DisplaySpec, msg_class: type[Image | CompressedImage]
    ) -> None:
        super().__init__(ctx, spec, msg_class)
        self._panel: viser.GuiImageHandle | None = None
        self._folder: viser.GuiFolderHandle | None = None

    def draw(self, msg: Image | CompressedImage) -> None:
        rgb = decode_compressed(msg) if isinstance(msg, CompressedImage) else image_rgb(msg)
        rgb = scaled(rgb, self.ctx.image_width)
        if self._panel is None:
            self._folder = self.ctx.server.gui.add_folder(f'Image {self.spec.topic}')
            with self._folder:
                self._panel = self.ctx.server.gui.add_image(
                    rgb, label=self.spec.topic, format='jpeg', jpeg_quality=70
                )
        else:
            self._panel.image = rgb

    def position(self, msg: MsgT) -> None:
        pass  # a panel, not in the scene

    def set_enabled(self, enabled: bool) -> None:
        super().set_enabled(enabled)
        if self._folder is not None:
            self._folder.visible = enabled

    def close(self) -> None:
        super().close()
        if self._folder is not None:
            self._folder.remove()


def decode_compressed(msg: CompressedImage) -> np.ndarray:
    """A CompressedImage (JPEG or PNG) as RGB, through Pillow."""
    from PIL import Image, UnidentifiedImageError

    try:
        with Image.open(io.BytesIO(bytes(msg.data))) as img:
            return np.asarray(img.convert('RGB'))
    except (UnidentifiedImageError, OSError) as e:
        raise ConvertError(f'cannot decode the compressed image: {e}') from None


CLASSES: dict[str, Callable[..., Shown]] = {
    'LaserScan': LaserScanDisplay,
    'PointCloud2': PointCloud2Display,
    'Pose': PoseDisplay,
    'PoseWithCovariance': PoseDisplay,
    'PoseArray': PoseArrayDisplay,
    'Path': PathDisplay,
    'Odometry': OdometryDisplay,
    'Map': MapDisplay,
    'Image': ImageDisplay,
}
