"""Faces whose library module may not be installed yet: names are looked up in it on first
use, and a missing module is an ImportError that names it (not an AttributeError)."""

from __future__ import annotations

import importlib
from collections.abc import Callable
from types import ModuleType


def library(candidates: tuple[str, ...], face: str, feature: str) -> ModuleType:
    """The first of `candidates` that imports; ImportError saying what is missing."""
    for name in candidates:
        try:
            return importlib.import_module(name)
        except ModuleNotFoundError as e:
            if e.name is None or not name.startswith(e.name):
                raise  # the module exists but something it needs does not
    raise ImportError(
        f'{face} needs {candidates[-1]} ({feature}), which this ros2lite does not have yet'
    )


def face(candidates: tuple[str, ...], face_name: str, feature: str) -> Callable[[str], object]:
    """A module `__getattr__` that maps every name onto the library module."""

    def __getattr__(name: str) -> object:
        if name.startswith('__'):
            raise AttributeError(name)
        return getattr(library(candidates, face_name, feature), name)

    return __getattr__
