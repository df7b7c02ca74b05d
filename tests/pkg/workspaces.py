"""Helpers that write source workspaces for the package tests (no build step anywhere)."""

from __future__ import annotations

from pathlib import Path

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3">
  <name>{name}</name>
  <version>1.2.3</version>
  <description>{name} for tests</description>
  <maintainer email="m@example.com">Maint</maintainer>
  <license>Apache-2.0</license>
  {depends}
  <export>
    <build_type>{build_type}</build_type>
  </export>
</package>
"""


# A node as a student writes it after `pkg create`, here against ros2lite's own API (the
# rclpy-named face of the same code is the compat directory's)
MINIMAL_PUBLISHER = '''
import ros2lite
from ros2lite.executors import ExternalShutdownException
from ros2lite.msgs.std_msgs.msg import String
from ros2lite.node import Node


class MinimalPublisher(Node):
    def __init__(self):
        super().__init__('minimal_publisher')
        self.publisher_ = self.create_publisher(String, 'topic', 10)
        self.i = 0
        self.timer = self.create_timer(0.1, self.timer_callback)

    def timer_callback(self):
        msg = String()
        msg.data = f'Hello World: {self.i}'
        self.publisher_.publish(msg)
        self.i += 1


def main(args=None):
    ros2lite.init(args=args)
    node = MinimalPublisher()
    try:
        ros2lite.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
'''


def write_package(
    directory: Path,
    name: str,
    *,
    build_type: str = 'ament_python',
    scripts: dict[str, str] | None = None,
    modules: dict[str, str] | None = None,
    depends: tuple[str, ...] = (),
) -> Path:
    """A package directory: package.xml, and for ament_python a setup.py declaring
    `scripts` (name -> 'module:function') and the `modules` files (relative path -> code)."""
    directory.mkdir(parents=True, exist_ok=True)
    deps = '\n  '.join(f'<depend>{d}</depend>' for d in depends)
    (directory / 'package.xml').write_text(
        PACKAGE_XML.format(name=name, build_type=build_type, depends=deps)
    )
    if build_type == 'ament_python':
        entries = ',\n'.join(f"            '{k} = {v}'" for k, v in (scripts or {}).items())
        (directory / 'setup.py').write_text(
            'from setuptools import find_packages, setup\n\n'
            f"package_name = '{name}'\n\n"
            'setup(\n'
            '    name=package_name,\n'
            "    packages=find_packages(exclude=['test']),\n"
            "    entry_points={'console_scripts': [\n"
            f'{entries}\n'
            '    ]},\n'
            ')\n'
        )
    for rel, code in (modules or {}).items():
        path = directory / rel
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(code)
    return directory
