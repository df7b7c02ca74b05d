"""Series named as rqt_plot names them: a topic and a field path in one text
(``/turtle1/pose/x``, ``/scan/ranges[0]``, ``/turtle1/pose/x:y``), checked against the
message type, and a message's numbers read along the path. What `plot` feeds its series by.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable
from dataclasses import dataclass

from ros2lite.exceptions import Ros2liteError
from ros2lite.interfaces import get_interface
from ros2lite.interfaces.parser import FieldType

__all__ = [
    'FieldPath',
    'PlotError',
    'SeriesSpec',
    'Step',
    'expand_specs',
    'field_types',
    'numeric',
    'split_last_fields',
    'split_topic',
]

_STEP = re.compile(r'([A-Za-z_][A-Za-z0-9_]*)((?:\[-?\d+\])*)$')
_INDEX = re.compile(r'\[(-?\d+)\]')


class PlotError(Ros2liteError, ValueError):
    """A series that cannot be plotted (unknown field, not a number, no such topic)."""


@dataclass(frozen=True)
class Step:
    """One field of a path, and the element indices after it (``ranges[3]``)."""

    name: str
    indices: tuple[int, ...] = ()

    def __str__(self) -> str:
        return self.name + ''.join(f'[{i}]' for i in self.indices)


@dataclass(frozen=True)
class FieldPath:
    """A path from a message to one of its values; empty means the message itself."""

    steps: tuple[Step, ...]

    @classmethod
    def parse(cls, text: str) -> FieldPath:
        """``pose/position/x``, ``ranges[0]``, ``pose.position.x``; PlotError if malformed."""
        parts = [p for p in re.split(r'[/.]', text) if p]
        steps = []
        for part in parts:
            m = _STEP.match(part)
            if m is None:
                raise PlotError(f"'{text}' is not a field path ('{part}' is no field name)")
            steps.append(Step(m.group(1), tuple(int(i) for i in _INDEX.findall(m.group(2)))))
        return cls(tuple(steps))

    def __str__(self) -> str:
        return '/'.join(str(s) for s in self.steps)

    def get(self, msg: object) -> object:
        """The value at the path in `msg` (IndexError past an array's end)."""
        value = msg
        for step in self.steps:
            value = getattr(value, step.name)
            for i in step.indices:
                value = value[i]
        return value

    def check(self, cls: type) -> str:
        """What the path names in messages of class `cls`: 'number' or 'array' (of numbers);
        PlotError saying why when it names a field that is missing or not numeric."""
        current: object = cls
        where = cls.__name__ if hasattr(cls, '__name__') else str(cls)
        for n, step in enumerate(self.steps):
            types = field_types(current)
            if types is None:
                raise PlotError(f"'{self}': '{where}' is a number, it has no field '{step.name}'")
            if step.name not in types:
                known = ', '.join(types) or 'none'
                raise PlotError(
                    f"'{self}': '{where}' has no field '{step.name}' (its fields: {known})"
                )
            ft = types[step.name]
            containers = 1 if ft.is_container else 0
            if len(step.indices) > containers:
                raise PlotError(f"'{self}': field '{step.name}' ({ft}) is not an array to index")
            last = n == len(self.steps) - 1
            if ft.is_container and not step.indices:
                if last and ft.is_primitive and _numeric_type(ft.base):
                    return 'array'
                raise PlotError(
                    f"'{self}': field '{step.name}' is an array ({ft}); name an element, "
                    f'as {step.name}[0]'
                )
            if ft.is_primitive:
                if not last:
                    raise PlotError(
                        f"'{self}': field '{step.name}' is a {ft.base}, it has no fields"
                    )
                if not _numeric_type(ft.base):
                    raise PlotError(f"'{self}': field '{step.name}' is a {ft.base}, not a number")
                return 'number'
            current = get_interface(ft.base)
            where = step.name
        if field_types(current) is not None:
            raise PlotError(
                f"'{self}' is a whole message ({getattr(current, '__name__', current)}); "
                f'name one of its numbers: {", ".join(_numeric_leaves(current))}'
            )
        return 'number'


def field_types(cls: object) -> dict[str, FieldType] | None:
    """Field name -> FieldType of a message class (None for anything else)."""
    names = getattr(cls, 'get_fields_and_field_types', None)
    if names is None:
        return None
    return dict(zip(names(), getattr(cls, 'SLOT_TYPES', ()), strict=True))


def _numeric_type(base: str) -> bool:
    return base not in ('string', 'wstring')


def _numeric_leaves(cls: object, prefix: str = '', limit: int = 8) -> list[str]:
    """The first few paths of numbers in messages of `cls` (for a hint)."""
    found: list[str] = []
    for name, ft in (field_types(cls) or {}).items():
        if len(found) >= limit:
            break
        if ft.is_container:
            continue
        if ft.is_primitive:
            if _numeric_type(ft.base):
                found.append(prefix + name)
        else:
            found += _numeric_leaves(get_interface(ft.base), f'{prefix}{name}/', limit - len(found))
    return found[:limit]


def numeric(value: object) -> float:
    """A message value as a plotted number (bools as 0/1, bytes' first byte)."""
    if isinstance(value, (bytes, bytearray)):
        return float(value[0]) if value else math.nan
    return float(value)  # type: ignore[arg-type]


@dataclass(frozen=True)
class SeriesSpec:
    """One plotted value: a topic and the path in its messages."""

    topic: str
    path: FieldPath

    def check(self, cls: type) -> str:
        """`path.check(cls)`, its errors naming the whole series."""
        try:
            return self.path.check(cls)
        except PlotError as e:
            raise PlotError(str(e).replace(f"'{self.path}'", f"'{self.label}'", 1)) from None

    @property
    def label(self) -> str:
        """rqt_plot's name for it: the topic and the path as one."""
        tail = str(self.path)
        return f'{self.topic}/{tail}' if tail else self.topic


def split_topic(text: str, topics: Iterable[str]) -> tuple[str, str] | None:
    """(topic, rest) for the longest of `topics` that `text` starts with at a field boundary,
    or None when none fits."""
    best: str | None = None
    for topic in topics:
        if (text == topic or text.startswith(topic.rstrip('/') + '/')) and (
            best is None or len(topic) > len(best)
        ):
            best = topic
    if best is None:
        return None
    return best, text[len(best) :].lstrip('/')


def expand_specs(text: str, topics: Iterable[str]) -> list[SeriesSpec]:
    """The series one argument names (``/t/pose/x:y`` is two); PlotError when no topic fits."""
    head, sep, tails = split_last_fields(text)
    found = split_topic(head, list(topics))
    if found is None:
        raise PlotError(f"no topic in the graph matches '{text}'")
    topic, rest = found
    if not sep:
        return [SeriesSpec(topic, FieldPath.parse(rest))]
    stem = rest.rsplit('/', 1)[0] if '/' in rest else ''
    paths = [rest] + [f'{stem}/{t}' if stem else t for t in tails]
    return [SeriesSpec(topic, FieldPath.parse(p)) for p in paths]


def split_last_fields(text: str) -> tuple[str, str, list[str]]:
    """``/t/a/x:y,z`` -> ('/t/a/x', ':', ['y', 'z']): the first series of a text and the
    siblings of its last field."""
    m = re.search(r'[:,]', text.rsplit('/', 1)[-1])
    if m is None:
        return text, '', []
    cut = len(text) - len(text.rsplit('/', 1)[-1]) + m.start()
    fields = [f for f in re.split(r'[:,]', text[cut + 1 :]) if f]
    return text[:cut], text[cut], fields
