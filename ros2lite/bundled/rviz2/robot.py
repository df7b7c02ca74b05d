"""The RobotModel display: the URDF on `/robot_description` (transient local, as
robot_state_publisher latches it), each link's visuals drawn under a frame that TF places
(the link's latest transform into the fixed frame, as RViz moves it)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ros2lite.bundled.rviz2.convert import ConvertError, wxyz
from ros2lite.bundled.rviz2.displays import Context, Display
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.tf2.math import quaternion_from_rpy

if TYPE_CHECKING:
    import viser

    from ros2lite.bundled.rviz2.config import DisplaySpec
    from ros2lite.urdf import Visual

DEFAULT_COLOUR = (204, 204, 204)  # RViz's grey for a visual with no material


class RobotModelDisplay(Display[String]):
    def __init__(self, ctx: Context, spec: DisplaySpec, msg_class: type[String]) -> None:
        super().__init__(ctx, spec, msg_class)
        self.links: dict[str, viser.FrameHandle] = {}

    def draw(self, msg: String) -> None:
        from ros2lite.urdf import UrdfError, parse_urdf

        try:
            robot = parse_urdf(msg.data)
        except UrdfError as e:
            raise ConvertError(f'robot description: {e}') from None
        for handle in self.links.values():
            handle.remove()
        self.links = {}
        problems: list[str] = []
        for name, link in robot.links.items():
            frame = self.ctx.server.scene.add_frame(
                f'{self.name}/{name.replace("/", ".")}', show_axes=False, visible=False
            )
            self.links[name] = frame
            for i, visual in enumerate(link.visuals):
                try:
                    self._visual(f'{frame.name}/v{i}', visual)
                except ConvertError as e:
                    problems.append(str(e))
        if problems:
            raise ConvertError(problems[0])

    def _visual(self, name: str, visual: Visual) -> None:
        scene = self.ctx.server.scene
        g = visual.geometry
        colour = (
            tuple(round(max(0.0, min(1.0, c)) * 255) for c in visual.rgba[:3])
            if visual.rgba is not None
            else DEFAULT_COLOUR
        )
        rgb = (colour[0], colour[1], colour[2])
        opacity = visual.rgba[3] if visual.rgba is not None and visual.rgba[3] < 1.0 else None
        at = {'position': visual.xyz, 'wxyz': wxyz(quaternion_from_rpy(*visual.rpy))}
        if g.kind == 'box':
            scene.add_box(name, rgb, g.size, opacity=opacity, **at)  # type: ignore[arg-type]
        elif g.kind == 'cylinder':
            scene.add_cylinder(name, g.radius, g.length, rgb, opacity=opacity, **at)  # type: ignore[arg-type]
        elif g.kind == 'sphere':
            scene.add_icosphere(name, g.radius, rgb, opacity=opacity, **at)  # type: ignore[arg-type]
        elif g.kind == 'mesh':
            from ros2lite.bundled.rviz2.markers import flat_visual, load_mesh

            mesh = load_mesh(g.filename)
            if visual.rgba is not None:
                mesh.visual = flat_visual(mesh, rgb)
            scene.add_mesh_trimesh(name, mesh, scale=g.scale, **at)  # type: ignore[arg-type]

    def position(self, msg: String) -> None:
        """Each link where TF has it now (RViz's RobotModel follows the latest TF)."""
        for link, frame in self.links.items():
            pose = self.ctx.place(link, 0)
            if pose is None:
                frame.visible = False
                self.ctx.status(self, f'no transform from link {link!r}')
                continue
            frame.visible = self.enabled
            frame.position, frame.wxyz = pose[0], wxyz(pose[1])

    def set_enabled(self, enabled: bool) -> None:
        super().set_enabled(enabled)
        for frame in self.links.values():
            frame.visible = enabled
