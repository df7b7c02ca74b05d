"""The `rclpy` tree of the compat directory: every face imports in a ROS shell and hands
out the library's own objects (one implementation); faces of library modules that are not
there yet say which one is missing."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from ros2lite.pkg.environment import COMPAT_DIR, ros_environment

FACES = sorted(
    '.'.join(p.relative_to(COMPAT_DIR).with_suffix('').parts).removesuffix('.__init__')
    for p in (COMPAT_DIR / 'rclpy').rglob('*.py')
    if not p.name.startswith('_') or p.name == '__init__.py'
)

CHECK = r'''
import importlib, sys
import ros2lite.logging, ros2lite.node, ros2lite.qos, ros2lite.clock
missing = []
for name in sys.argv[1:]:
    module = importlib.import_module(name)
    for attr in getattr(module, '__all__', []):
        getattr(module, attr)
import rclpy, rclpy.node, rclpy.qos, rclpy.clock, rclpy.logging
assert rclpy.node.Node is ros2lite.node.Node
assert rclpy.qos.QoSProfile is ros2lite.qos.QoSProfile
assert rclpy.clock.ROSClock is ros2lite.clock.ROSClock
assert rclpy.logging is ros2lite.logging
assert rclpy.executors.MultiThreadedExecutor.__module__ == 'ros2lite.executors'
for face in ('rclpy.lifecycle', 'rclpy.service_introspection'):
    try:
        importlib.import_module(face).SOMETHING
    except ImportError as e:
        print(e)
    except AttributeError:
        print(face, 'served by the library')
'''


def test_every_face_imports_and_maps_to_the_library() -> None:
    assert 'rclpy.node' in FACES and 'rclpy.action.server' in FACES and len(FACES) > 55
    env = {k: v for k, v in os.environ.items() if k != 'PYTHONPATH'}
    env.update(ros_environment(env))
    proc = subprocess.run(
        [sys.executable, '-c', CHECK, *FACES],
        capture_output=True,
        text=True,
        timeout=60,
        env=env,
        cwd=Path(__file__).parent,
    )
    assert proc.returncode == 0, proc.stderr
    for line in proc.stdout.splitlines():
        assert 'served by the library' in line or 'which this ros2lite does not have yet' in line
