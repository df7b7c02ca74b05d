"""Hypothesis strategies that build random ros2lite messages of any type."""

from __future__ import annotations

import struct
from typing import Any

from hypothesis import strategies as st

from ros2lite.interfaces.classes import get_interface
from ros2lite.interfaces.parser import INT_RANGES, FieldType
from ros2lite.interfaces.registry import default_registry

_f32 = st.floats(width=32, allow_nan=False)
_f64 = st.floats(allow_nan=False)
_text = st.text(st.characters(codec='utf-8', exclude_characters='\x00'), max_size=12)


def _scalar(ft: FieldType) -> st.SearchStrategy[Any]:
    base = ft.base
    if base == 'bool':
        return st.booleans()
    if base == 'byte':
        return st.binary(min_size=1, max_size=1)
    if base in INT_RANGES:
        lo, hi = INT_RANGES[base]
        return st.integers(lo, hi)
    if base == 'float32':
        return _f32.map(lambda v: struct.unpack('<f', struct.pack('<f', v))[0])
    if base == 'float64':
        return _f64
    if base in ('string', 'wstring'):
        s = _text
        if ft.string_bound:
            s = st.text(
                st.characters(codec='utf-8', exclude_characters='\x00'), max_size=ft.string_bound
            )
        return s
    return message(base)


def _value(ft: FieldType) -> st.SearchStrategy[Any]:
    if not ft.is_container:
        return _scalar(ft)
    elem = _scalar(ft.element)
    if ft.container == 'array':
        return st.lists(elem, min_size=ft.size, max_size=ft.size)
    if ft.container == 'bounded':
        return st.lists(elem, max_size=ft.size)
    return st.lists(elem, max_size=4)


_CACHE: dict[str, st.SearchStrategy[Any]] = {}


def message(name: str) -> st.SearchStrategy[Any]:
    """Strategy for random instances of message type `name`."""
    if name not in _CACHE:
        mdef = default_registry().message(name)
        cls = get_interface(name)
        _CACHE[name] = st.deferred(
            lambda: st.builds(cls, **{f.name: _value(f.type) for f in mdef.fields})
        )
    return _CACHE[name]
