"""Bundled interface definitions, where interface packages come from, and the import hook.

`from ros2lite.msgs.std_msgs.msg import String` works for every package on the search path
(:func:`search_root_dirs`): a meta-path finder builds the `<pkg>` and `<pkg>.msg|srv|action`
modules on first import, and classes on first attribute access.

:func:`install_top_level` adds the same finder without the prefix, so that code written for
rclpy imports `from std_msgs.msg import String`. Only ``ros2lite env`` (its compat directory)
and the children of ``ros2lite run`` install it: a plain ``import ros2lite`` never serves
names that belong to a real ROS install. That finder is consulted for every import of such a
process, so it answers "not mine" from a few cached directory checks, importing nothing.
"""

from __future__ import annotations

import importlib.machinery
import os
import sys
import types
from collections.abc import Sequence
from typing import Any

_PREFIX = __name__ + '.'
_KINDS = ('msg', 'srv', 'action')


def search_root_dirs() -> list[str]:
    """Directories whose children are interface packages, in priority order, as strings:
    :func:`ros2lite.pkg.index.interface_roots` owns the rule (the registry follows it too).
    Worked out once per value of the variables it reads, since the top-level finder asks on
    every import of the process."""
    from ros2lite.pkg.index import INTERFACE_PATH_ENV, interface_roots

    key = (os.environ.get(INTERFACE_PATH_ENV), os.environ.get('AMENT_PREFIX_PATH'))
    roots = _roots.get(key)
    if roots is None:
        _roots.clear()
        roots = _roots[key] = [str(root) for root in interface_roots()]
    return list(roots)


# the variables' values → the roots they give
_roots: dict[tuple[str | None, str | None], list[str]] = {}

# name → could it be an interface package (a directory with msg/srv/action in some root)
_maybe: dict[tuple[tuple[str, ...], str], bool] = {}


def _may_be_package(name: str) -> bool:
    roots = tuple(search_root_dirs())
    key = (roots, name)
    hit = _maybe.get(key)
    if hit is None:
        hit = _maybe[key] = any(
            os.path.isdir(os.path.join(root, name, kind)) for root in roots for kind in _KINDS
        ) or name in _workspace_packages()
    return hit


_workspaces: dict[tuple[str | None, str], frozenset[str]] = {}


def _workspace_packages() -> frozenset[str]:
    from ros2lite.pkg.index import workspace_interface_packages
    from ros2lite.pkg.workspace import WORKSPACE_ENV

    key = (os.environ.get(WORKSPACE_ENV), os.getcwd())
    names = _workspaces.get(key)
    if names is None:
        names = _workspaces[key] = frozenset(workspace_interface_packages())
    return names


def _split(module: str, prefix: str) -> tuple[str, str]:
    pkg, kind = module[len(prefix) :].split('.')
    return pkg, kind


class _InterfaceModule(types.ModuleType):
    """A `<pkg>.<kind>` module whose attributes are interface classes built on demand."""

    _prefix = _PREFIX

    def __getattr__(self, attr: str) -> Any:
        if attr.startswith('__'):
            raise AttributeError(attr)
        from ros2lite.interfaces import get_interface
        from ros2lite.interfaces.errors import InterfaceError

        pkg, kind = _split(self.__name__, self._prefix)
        try:
            cls = get_interface(f'{pkg}/{kind}/{attr}')
        except InterfaceError:
            raise AttributeError(
                f"module '{self.__name__}' has no interface '{attr}' "
                f'(no {kind} file {attr} in package {pkg})'
            ) from None
        setattr(self, attr, cls)
        return cls

    def __dir__(self) -> list[str]:
        from ros2lite.interfaces.registry import default_registry

        pkg, kind = _split(self.__name__, self._prefix)
        names = default_registry().package_interfaces(pkg)
        return [n.rsplit('/', 1)[1] for n in names if n.split('/')[1] == kind]


class _Loader:
    """Makes the package and kind modules (nothing to execute)."""

    def __init__(self, prefix: str) -> None:
        self.prefix = prefix

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        parts = spec.name[len(self.prefix) :].split('.')
        if len(parts) == 1:
            module = types.ModuleType(spec.name)
            module.__path__ = list(spec.submodule_search_locations or [])
            return module
        module = _InterfaceModule(spec.name)
        module._prefix = self.prefix
        return module

    def exec_module(self, module: types.ModuleType) -> None:
        return None


class InterfaceFinder:
    """A meta-path finder: claims `<prefix><pkg>` and `<prefix><pkg>.<kind>` for known
    interface packages."""

    def __init__(self, prefix: str) -> None:
        self.prefix = prefix

    def find_spec(
        self,
        fullname: str,
        path: Sequence[str] | None,
        target: types.ModuleType | None = None,
    ) -> importlib.machinery.ModuleSpec | None:
        if not fullname.startswith(self.prefix):
            return None
        parts = fullname[len(self.prefix) :].split('.')
        if len(parts) > 2 or (len(parts) == 2 and parts[1] not in _KINDS):
            return None
        if not self.prefix and (
            parts[0] in sys.stdlib_module_names or not _may_be_package(parts[0])
        ):
            return None  # every other import of the process: answered without the registry
        from ros2lite.interfaces.registry import default_registry

        if parts[0] not in default_registry().packages():
            return None
        loader: Any = _Loader(self.prefix)  # a loader by protocol (importlib.abc costs ~10 ms)
        spec = importlib.machinery.ModuleSpec(fullname, loader, is_package=len(parts) == 1)
        if len(parts) == 1 and not self.prefix:
            # a Python package of the same name elsewhere on the path keeps its other modules
            # importable (`my_interfaces.helpers`); its msg/srv/action are ours
            other = importlib.machinery.PathFinder.find_spec(fullname)
            if other is not None and fullname in _our_modules():
                return None  # never shadow what ros2lite itself imports (a package `click`)
            if other is not None and other.submodule_search_locations:
                spec.submodule_search_locations = list(other.submodule_search_locations)
        return spec


_ours: frozenset[str] | None = None


def _our_modules() -> frozenset[str]:
    """The top-level modules of ros2lite and of everything it depends on (its requirements,
    theirs, …; extras left out), from the installed metadata: an interface package of the
    same name must not take their place. Read once, and only for a name that is both an
    interface package and something else on the path."""
    global _ours
    if _ours is None:
        import re
        from importlib import metadata

        def key(name: str) -> str:
            return re.sub(r'[-_.]+', '-', name).lower()

        seen: set[str] = set()
        todo = ['ros2lite']
        while todo:
            dist = key(todo.pop())
            if dist in seen:
                continue
            seen.add(dist)
            try:
                requires = metadata.requires(dist) or []
            except metadata.PackageNotFoundError:
                continue
            for req in requires:
                name = re.match(r'[A-Za-z0-9][A-Za-z0-9._-]*', req.strip())
                if name and 'extra ==' not in req.replace('extra==', 'extra =='):
                    todo.append(name.group())
        modules = {'ros2lite'}
        for module, dists in metadata.packages_distributions().items():
            if any(key(d) in seen for d in dists):
                modules.add(module)
        _ours = frozenset(modules)
    return _ours


def install_top_level() -> None:
    """Serve every interface package as a top-level module (`import std_msgs.msg`), ahead of
    any other finder, so a real ROS install on the same path never mixes its generated
    classes with ros2lite's."""
    if not any(isinstance(f, InterfaceFinder) and not f.prefix for f in sys.meta_path):
        sys.meta_path.insert(0, InterfaceFinder(''))


if not any(isinstance(f, InterfaceFinder) and f.prefix == _PREFIX for f in sys.meta_path):
    sys.meta_path.insert(0, InterfaceFinder(_PREFIX))
