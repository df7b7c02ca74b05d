"""ros2lite's colcon extensions, registered through colcon's entry points (pyproject.toml).

Without a ROS install an `ament_cmake` package cannot be configured: colcon-ros would run
CMake, which finds no `ament_cmake`, and the failure stops every other package. So, when no
ROS install provides ament_cmake, packages of that build type are identified as one of two
types of ours, with colcon-ros's dependencies from package.xml kept (the `ros.` prefix):

- ``ros.ament_cmake.interfaces``: its CMakeLists calls `rosidl_generate_interfaces`; the
  interface files are checked and installed as ROS installs them (:mod:`.rosidl`), with the
  ament index entries and an AMENT_PREFIX_PATH hook, so `source install/setup.bash` makes
  them known to every shell and node;
- ``ros.ament_cmake.files``: it only copies files (`install(DIRECTORY launch ...)`, a bringup
  package); they are installed as CMake lays them out, with the same index entry and hook;
- ``ros.ament_cmake.unbuilt``: C++ (or nothing) to build; one line says so and the package is
  passed over, so the rest of the workspace builds and the status stays 0.

With a ROS install (cmake on PATH and ament_cmake on a prefix path) nothing is changed: the
real ament_cmake builds everything, as on ROS.

`colcon test` of an ament_python package runs pytest in the environment `ros2lite run`
gives nodes (the compat faces first on PYTHONPATH), so a package's tests import `rclpy`,
its messages and the linters as on ROS (compat/'s `ament_copyright`, and `ament_flake8` where
PyPI's wheel does not run), unless a ROS install's linters are sourced.

This module is imported by colcon, never by ros2lite itself; it imports nothing of the CLI.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import shutil
import sys
from collections.abc import Callable, Mapping
from pathlib import Path

from colcon_core.environment import create_environment_scripts
from colcon_core.logging import colcon_logger
from colcon_core.package_descriptor import PackageDescriptor
from colcon_core.package_identification import PackageIdentificationExtensionPoint
from colcon_core.plugin_system import SkipExtensionException, satisfies_version
from colcon_core.shell import create_environment_hook
from colcon_core.task import TaskContext, TaskExtensionPoint, create_file, install
from colcon_core.task.python.test import PythonTestingStepExtensionPoint
from colcon_core.task.python.test.pytest import PytestPythonTestingStep
from colcon_ros.package_identification.ros import get_package_with_build_type

from ros2lite.interfaces.registry import Registry
from ros2lite.pkg.environment import ros_environment

from .cmake import CMakeError, file_install_plan, mentions_rosidl, read_cmake_package
from .rosidl import InterfacePackageError, check_interfaces, install_plan, resource_index_entry

__all__ = [
    'FILES_TYPE',
    'INTERFACES_TYPE',
    'UNBUILT_TYPE',
    'AmentCmakeIdentification',
    'InterfacePackageBuildTask',
    'InterfacePackageTestTask',
    'RosEnvironmentPytestStep',
    'UnbuiltPackageBuildTask',
    'UnbuiltPackageTestTask',
    'ros_ament_cmake_found',
]

logger = colcon_logger.getChild('ros2lite')

INTERFACES_TYPE = 'ros.ament_cmake.interfaces'
FILES_TYPE = 'ros.ament_cmake.files'
UNBUILT_TYPE = 'ros.ament_cmake.unbuilt'
_CONFIGS = ('ament_cmakeConfig.cmake', 'ament_cmake-config.cmake')
_INDEX = Path('share') / 'ament_index' / 'resource_index' / 'packages'
# linters compat/ has faces of, for where PyPI has no (fitting) wheel
_FACES = ('ament_copyright', 'ament_flake8')


def _prefixes(env: Mapping[str, str]) -> list[Path]:
    out: list[Path] = []
    for var in ('AMENT_PREFIX_PATH', 'CMAKE_PREFIX_PATH'):
        out += [Path(p) for p in env.get(var, '').split(os.pathsep) if p]
    return out


def ros_ament_cmake_found(env: Mapping[str, str] | None = None) -> bool:
    """Can this environment build ament_cmake packages (a sourced ROS install and CMake)?"""
    environ = os.environ if env is None else env
    if shutil.which('cmake', path=environ.get('PATH')) is None:
        return False
    return any(
        (prefix / 'share' / 'ament_cmake' / 'cmake' / name).is_file()
        for prefix in _prefixes(environ)
        for name in _CONFIGS
    )


def _ros_linters_sourced(env: Mapping[str, str]) -> bool:
    """Is a ROS install's ament_copyright on the test's prefix path (then it is used)?"""
    return any((prefix / _INDEX / 'ament_copyright').is_file() for prefix in _prefixes(env))


class AmentCmakeIdentification(PackageIdentificationExtensionPoint):
    """Identify `ament_cmake` packages that ros2lite builds or names, where no ROS install
    could build them."""

    # above colcon-ros's identification (150), which would claim them as ros.ament_cmake
    PRIORITY = 160

    def __init__(self) -> None:
        super().__init__()
        satisfies_version(PackageIdentificationExtensionPoint.EXTENSION_POINT_VERSION, '^1.0')
        if ros_ament_cmake_found():
            raise SkipExtensionException('a ROS install builds ament_cmake packages here')

    def identify(self, desc: PackageDescriptor) -> None:
        """Claim an ament_cmake package as ros.ament_cmake.interfaces or .unbuilt."""
        if desc.type is not None and desc.type != 'ros':
            return
        path = Path(desc.path)
        if (path / 'AMENT_IGNORE').exists() or (path / 'CATKIN_IGNORE').exists():
            return  # colcon-ros ignores the location
        # colcon-ros's own reading of package.xml (cached), so both agree on name and type
        manifest, build_type = get_package_with_build_type(str(path))
        if manifest is None or build_type != 'ament_cmake':
            return  # not a ROS package, another build type, or a manifest colcon-ros reports
        try:
            cmake = read_cmake_package(path, manifest.name)
        except CMakeError:  # the build task names the problem, or the skip line does
            desc.type = INTERFACES_TYPE if mentions_rosidl(path) else UNBUILT_TYPE
        else:
            if cmake.has_interfaces:
                desc.type = INTERFACES_TYPE
            elif cmake.installs and not cmake.unbuilt:
                desc.type = FILES_TYPE  # launch files, configs, scripts: copies only
            else:
                desc.type = UNBUILT_TYPE
        if desc.name is None:
            desc.name = manifest.name


def _where_to_build(name: str, what: str, skipped: str = 'it is skipped') -> str:
    return (
        f'{name}: {what}; ros2lite runs Python nodes and builds interface packages only, '
        f'so {skipped}: build it in a ROS 2 install (source /opt/ros/<distro>/setup.bash, '
        'then colcon build)'
    )


class _Task(TaskExtensionPoint):
    def __init__(self) -> None:
        super().__init__()
        satisfies_version(TaskExtensionPoint.EXTENSION_POINT_VERSION, '^1.0')


class InterfacePackageBuildTask(_Task):
    """Build an ament_cmake package whose CMakeLists only generates interfaces and copies
    files: check and install the interfaces, copy what install() names, then the manifest,
    the ament index entries and the AMENT_PREFIX_PATH hook, as ament_cmake would."""

    async def build(self) -> int:
        """Check every interface file, then install them and the copied files."""
        args = self.context.args
        pkg = self.context.pkg
        path = Path(args.path)
        try:
            cmake = read_cmake_package(path, pkg.name)
            files = []
            if cmake.has_interfaces:
                files = check_interfaces(path, pkg.name, cmake, self._provider())
            copies = file_install_plan(path, cmake.installs)
        except (CMakeError, InterfacePackageError) as e:
            logger.error(str(e))
            return 1
        for source, destination in install_plan(pkg.name, files):
            install(args, source, destination)
        for source, destination, executable in copies:
            install(args, source, destination)
            target = Path(args.install_base) / destination
            if executable and not target.is_symlink():
                target.chmod(0o755)
        create_file(args, f'share/ament_index/resource_index/packages/{pkg.name}')
        if files:
            create_file(
                args,
                f'share/ament_index/resource_index/rosidl_interfaces/{pkg.name}',
                content=resource_index_entry(files),
            )
        hooks = create_environment_hook(
            'ament_prefix_path',
            Path(args.install_base),
            pkg.name,
            'AMENT_PREFIX_PATH',
            '',
            mode='prepend',
        )
        create_environment_scripts(pkg, args, additional_hooks=hooks)
        if cmake.unbuilt:
            done = f'its {len(files)} interfaces are installed'
            if copies:
                done += f' with {len(copies)} files'
            logger.warning(
                _where_to_build(
                    pkg.name,
                    f'{done}, but its CMakeLists.txt also builds C++ ({cmake.unbuilt_summary()})',
                    skipped='that part is skipped',
                )
            )
        return 0

    def _provider(self) -> Callable[[str], bool]:
        """Does a dependency built in this workspace, or any package ros2lite finds, define
        `pkg/msg/Name`?"""
        prefixes = {name: Path(p) for name, p in (self.context.dependencies or {}).items()}
        registry = Registry()

        def provides(name: str) -> bool:
            pkg, kind, short = name.split('/')
            prefix = prefixes.get(pkg)
            if prefix is not None:
                return (prefix / 'share' / pkg / kind / f'{short}.{kind}').is_file()
            return registry.exists(name)

        return provides


class InterfacePackageTestTask(_Task):
    """An interface (or files-only) package has nothing ros2lite tests: the build checked
    its files, and its CMake tests (ament_lint_auto) need CMake."""

    async def test(self) -> int:
        """Nothing to run."""
        return 0


class UnbuiltPackageBuildTask(_Task):
    """Say in one line that a C++ (or empty) ament_cmake package is not built here."""

    async def build(self) -> int:
        """Name the package and where to build it; the workspace goes on."""
        args = self.context.args
        pkg = self.context.pkg
        try:
            cmake = read_cmake_package(Path(args.path), pkg.name)
            what = (
                f'a C++ package (ament_cmake: {cmake.unbuilt_summary()})'
                if cmake.unbuilt
                else 'a C++ package (ament_cmake, nothing to compile yet)'
            )
        except CMakeError as e:
            what = f'a C++ package (ament_cmake; its CMakeLists.txt: {e})'
        logger.warning(_where_to_build(pkg.name, what))
        return 0


class UnbuiltPackageTestTask(_Task):
    """Its tests would need its CMake build; passed over like the build."""

    async def test(self) -> int:
        """Nothing was built, so nothing is tested."""
        logger.warning(f'{self.context.pkg.name}: not built by ros2lite, so not tested')
        return 0


class RosEnvironmentPytestStep(PythonTestingStepExtensionPoint):
    """pytest for a ROS Python package, in the environment `ros2lite run` gives its nodes."""

    # above colcon-core's pytest step (200), which it wraps
    PRIORITY = 210

    def __init__(self) -> None:
        super().__init__()
        satisfies_version(PythonTestingStepExtensionPoint.EXTENSION_POINT_VERSION, '^1.0')
        self._pytest = PytestPythonTestingStep()  # SkipExtensionException without pytest

    def add_arguments(self, *, parser: argparse.ArgumentParser) -> None:
        """colcon-core's pytest step adds --pytest-args; nothing more here."""

    def match(
        self, context: TaskContext, env: Mapping[str, str], setup_py_data: Mapping[str, object]
    ) -> bool:
        """A ROS Python package whose tests pytest runs, where no ROS install's linters are
        sourced."""
        if not str(context.pkg.type).startswith('ros.') or _ros_linters_sourced(env):
            return False
        return bool(self._pytest.match(context, env, setup_py_data))

    async def step(
        self, context: TaskContext, env: Mapping[str, str], setup_py_data: Mapping[str, object]
    ) -> int | None:
        """colcon-core's pytest run, with the compat faces on PYTHONPATH and the linter
        markers registered."""
        test_env = dict(env)
        test_env.update(ros_environment(test_env))
        # the faces' markers, where no installed linter registers its own (entry points)
        plugins = [p for p in test_env.get('PYTEST_PLUGINS', '').split(',') if p]
        for face in _FACES:
            if importlib.util.find_spec(face) is None:
                plugins.append(f'{face}.pytest_marker')
        if plugins:
            test_env['PYTEST_PLUGINS'] = ','.join(dict.fromkeys(plugins))
        test_env.setdefault('PYTHONDONTWRITEBYTECODE', '1')
        logger.info(f"Testing '{context.pkg.name}' with ros2lite's faces ({sys.executable})")
        return await self._pytest.step(context, test_env, setup_py_data)
