"""One element of an XML or YAML launch file, read the same way whichever the format.

XML: an element; attributes are strings, nested actions are child elements, a node's
`<param>`/`<remap>`/`<env>` and an include's `<arg>` are child elements by tag.
YAML: a one-key mapping `{type: {attributes…}}`; nested actions are the `children` list,
and `param`/`remap`/`env`/`arg` are lists of mappings.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET

from ..errors import InvalidFrontendLaunchFileError
from ..substitutions import Substitution, TextSubstitution
from .substitutions import parse_substitutions

__all__ = ['Entity', 'XmlEntity', 'YamlEntity']

_TRUE = ('true', '1', 'yes')
_FALSE = ('false', '0', 'no')


class Entity:
    """Attributes and children of one launch file element."""

    type_name: str = ''
    where: str = ''

    def raw(self, name: str) -> object:
        """The attribute as written (None when absent)."""
        raise NotImplementedError

    def children(self) -> list[Entity]:
        """Nested actions (of `<launch>`, `<group>`, `<timer>`)."""
        raise NotImplementedError

    def child_list(self, tag: str) -> list[Entity]:
        """Sub-elements of one kind (`param`, `remap`, `env`, `arg`, `choice`)."""
        raise NotImplementedError

    def error(self, message: str) -> InvalidFrontendLaunchFileError:
        """An error naming the file and the element, for `raise`."""
        return InvalidFrontendLaunchFileError(f'{self.where}: <{self.type_name}>: {message}')

    def _required(self, name: str, optional: bool) -> object:
        value = self.raw(name)
        if value is None and not optional:
            raise self.error(f"missing attribute '{name}'")
        return value

    def subs(self, name: str, *, optional: bool = True) -> list[Substitution] | None:
        """The attribute as substitutions (`$(var x)` …)."""
        value = self._required(name, optional)
        if value is None:
            return None
        if isinstance(value, bool):
            return [TextSubstitution(text=str(value).lower())]
        if isinstance(value, (int, float)):
            return [TextSubstitution(text=str(value))]
        if not isinstance(value, str):
            raise self.error(f"attribute '{name}' must be text, not {type(value).__name__}")
        return parse_substitutions(value)

    def text(self, name: str, *, optional: bool = True) -> str | None:
        """The attribute as plain text (no substitutions)."""
        value = self._required(name, optional)
        if value is None:
            return None
        if isinstance(value, bool):
            return str(value).lower()
        return str(value)

    def flag(self, name: str, default: bool) -> bool:
        """A boolean attribute ('true'/'false', '1'/'0', 'yes'/'no'), or `default` when absent."""
        value = self.raw(name)
        if value is None:
            return default
        if isinstance(value, bool):
            return value
        lowered = str(value).strip().lower()
        if lowered in _TRUE:
            return True
        if lowered in _FALSE:
            return False
        raise self.error(f"attribute '{name}' must be true or false, not '{value}'")

    def number(self, name: str, *, optional: bool = True) -> float | None:
        """A numeric attribute (None when absent and optional)."""
        value = self._required(name, optional)
        if value is None:
            return None
        try:
            if not isinstance(value, (str, int, float)):
                raise TypeError(value)
            return float(value)
        except (TypeError, ValueError):
            raise self.error(f"attribute '{name}' must be a number, not '{value}'") from None

    def value(self, name: str) -> object:
        """A parameter value: YAML keeps its type; text may hold substitutions."""
        return self.raw(name)


class XmlEntity(Entity):
    """An element of an XML launch file."""

    def __init__(self, element: ET.Element, where: str) -> None:
        self.element = element
        self.type_name = element.tag
        self.where = where

    def raw(self, name: str) -> object:
        """The attribute's text (None when absent)."""
        return self.element.get(name)

    def children(self) -> list[Entity]:
        """Every sub-element, as entities."""
        return [XmlEntity(child, self.where) for child in self.element]

    def child_list(self, tag: str) -> list[Entity]:
        """The sub-elements with tag `tag`."""
        return [XmlEntity(child, self.where) for child in self.element if child.tag == tag]


class YamlEntity(Entity):
    """A mapping of a YAML launch file (its attributes and nested lists)."""

    def __init__(self, type_name: str, body: object, where: str) -> None:
        if body is None:
            body = {}
        if not isinstance(body, dict):
            raise InvalidFrontendLaunchFileError(
                f'{where}: {type_name}: expected a mapping of attributes, got {type(body).__name__}'
            )
        self.type_name = type_name
        self.body = body
        self.where = where

    def raw(self, name: str) -> object:
        """The key's value as YAML typed it (None when absent)."""
        return self.body.get(name)

    def children(self) -> list[Entity]:
        """The actions of its `children` list."""
        return _entities(self.body.get('children') or [], self.where)

    def child_list(self, tag: str) -> list[Entity]:
        """The mappings of its list `tag`."""
        items = self.body.get(tag) or []
        if not isinstance(items, list):
            raise self.error(f"'{tag}' must be a list")
        return [YamlEntity(tag, item, self.where) for item in items]


def _entities(items: object, where: str) -> list[Entity]:
    if not isinstance(items, list):
        raise InvalidFrontendLaunchFileError(f'{where}: expected a list of actions')
    out: list[Entity] = []
    for item in items:
        if not isinstance(item, dict) or len(item) != 1:
            raise InvalidFrontendLaunchFileError(
                f'{where}: each action is a mapping with one key (its type), got {item!r}'
            )
        ((kind, body),) = item.items()
        out.append(YamlEntity(str(kind), body, where))
    return out


def yaml_root(document: object, where: str) -> list[Entity]:
    """The actions of a YAML launch document (`launch: [...]`)."""
    if not isinstance(document, dict) or 'launch' not in document:
        raise InvalidFrontendLaunchFileError(f"{where}: a YAML launch file starts with 'launch:'")
    return _entities(document['launch'] or [], where)
