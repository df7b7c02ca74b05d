"""Bundled interface definitions, importable rclpy-style.

`from ros2lite.msgs.std_msgs.msg import String` works for every package on the search path
(bundled, ``ROS2LITE_INTERFACE_PATH``, ``AMENT_PREFIX_PATH``): a meta-path finder builds the
`<pkg>` and `<pkg>.msg|srv|action` modules on first import, and classes on first attribute access.
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


class _InterfaceModule(types.ModuleType):
    """A `<pkg>.<kind>` module whose attributes are interface classes built on demand."""

    def __getattr__(self, attr: str) -> Any:
        if attr.startswith('__'):
            raise AttributeError(attr)
        from ros2lite.interfaces import get_interface
        from ros2lite.interfaces.errors import InterfaceError
        pkg, kind = self.__name__[len(_PREFIX):].split('.')
        try:
            cls = get_interface(f'{pkg}/{kind}/{attr}')
        except InterfaceError:
            raise AttributeError(
                f"module '{self.__name__}' has no interface '{attr}'") from None
        setattr(self, attr, cls)
        return cls

    def __dir__(self) -> list[str]:
        from ros2lite.interfaces.registry import default_registry
        pkg, kind = self.__name__[len(_PREFIX):].split('.')
        names = default_registry().package_interfaces(pkg)
        return [n.rsplit('/', 1)[1] for n in names if n.split('/')[1] == kind]


class _Loader(importlib.abc.Loader):
    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        parts = spec.name[len(_PREFIX):].split('.')
        if len(parts) == 1:
            module = types.ModuleType(spec.name)
            module.__path__ = []
            return module
        return _InterfaceModule(spec.name)

    def exec_module(self, module: types.ModuleType) -> None:
        return None


class _Finder(importlib.abc.MetaPathFinder):
    """Claims `ros2lite.msgs.<pkg>` and `ros2lite.msgs.<pkg>.<kind>` for known packages."""

    def find_spec(self, fullname: str, path: Sequence[str] | None,
                  target: types.ModuleType | None = None
                  ) -> importlib.machinery.ModuleSpec | None:
        if not fullname.startswith(_PREFIX):
            return None
        parts = fullname[len(_PREFIX):].split('.')
        if len(parts) > 2 or (len(parts) == 2 and parts[1] not in _KINDS):
            return None
        from ros2lite.interfaces.registry import default_registry
        if parts[0] not in default_registry().packages():
            return None
        return importlib.machinery.ModuleSpec(fullname, _Loader(), is_package=len(parts) == 1)


if not any(isinstance(f, _Finder) for f in sys.meta_path):
    sys.meta_path.insert(0, _Finder())
