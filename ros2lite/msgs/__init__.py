"""Bundled interface definitions, importable rclpy-style.

`from ros2lite.msgs.std_msgs.msg import String` works for every package on the search path
(bundled, ``ROS2LITE_INTERFACE_PATH``, ``AMENT_PREFIX_PATH``): a meta-path finder builds the
`<pkg>` and `<pkg>.msg|srv|action` modules on first import, and classes on first attribute access.

:func:`install_top_level` adds the same finder without the prefix, so that code written for
rclpy imports `from std_msgs.msg import String`. Only ``ros2lite env`` (its compat directory)
and the children of ``ros2lite run`` install it: a plain ``import ros2lite`` never serves
names that belong to a real ROS install. Where packages come from is the registry's one rule
(:func:`ros2lite.interfaces.registry.search_roots`); a new source of packages plugs in there.
"""

from __future__ import annotations

import importlib.abc
import importlib.machinery
import sys
import types
from collections.abc import Sequence
from typing import Any

_PREFIX = __name__ + '.'
_KINDS = ('msg', 'srv', 'action')


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


class _Loader(importlib.abc.Loader):
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


class InterfaceFinder(importlib.abc.MetaPathFinder):
    """Claims `<prefix><pkg>` and `<prefix><pkg>.<kind>` for known interface packages."""

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
        if not self.prefix and parts[0] in sys.stdlib_module_names:
            return None  # the common case of every import, answered without a lookup
        from ros2lite.interfaces.registry import default_registry

        if parts[0] not in default_registry().packages():
            return None
        spec = importlib.machinery.ModuleSpec(
            fullname, _Loader(self.prefix), is_package=len(parts) == 1
        )
        if len(parts) == 1 and not self.prefix:
            # a Python package of the same name elsewhere on the path keeps its other modules
            # importable (`my_interfaces.helpers`); its msg/srv/action are ours
            other = importlib.machinery.PathFinder.find_spec(fullname)
            if other is not None and other.submodule_search_locations:
                spec.submodule_search_locations = list(other.submodule_search_locations)
        return spec


def install_top_level() -> None:
    """Serve every interface package as a top-level module (`import std_msgs.msg`), ahead of
    any other finder, so a real ROS install on the same path never mixes its generated
    classes with ros2lite's."""
    if not any(isinstance(f, InterfaceFinder) and not f.prefix for f in sys.meta_path):
        sys.meta_path.insert(0, InterfaceFinder(''))


if not any(isinstance(f, InterfaceFinder) and f.prefix == _PREFIX for f in sys.meta_path):
    sys.meta_path.insert(0, InterfaceFinder(_PREFIX))
