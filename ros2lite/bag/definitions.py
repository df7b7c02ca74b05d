"""Types a bag brings with it: the `ros2msg` texts stored in its schemas, as a registry.

A bag recorded elsewhere may hold types this machine has never seen, or other versions of ones
it has. Its schemas carry the full definition text (the type, then `MSG:`/`SRV:` sections for
every dependency), which is enough to build codecs: `BagTypes` is a registry that answers from
those texts first and from the local search path for anything they leave out.
"""

from __future__ import annotations

import re
from typing import ClassVar

from ros2lite.interfaces.errors import InterfaceError
from ros2lite.interfaces.parser import MessageDef, parse_message, parse_service
from ros2lite.interfaces.registry import Registry, default_registry, event_message, normalize_name

__all__ = ["BagTypes", "parse_definition"]

_SEPARATOR = re.compile(r"^={3,}\s*$", re.MULTILINE)
_HEADER = re.compile(r"^\s*(MSG|SRV|IDL):\s*(\S+)\s*$")


def _add_service(out: dict[str, MessageDef], name: str, text: str) -> None:
    svc = parse_service(text, name)
    out[name + "_Request"] = svc.request
    out[name + "_Response"] = svc.response
    out[name + "_Event"] = event_message(name, svc.request.name, svc.response.name)


def parse_definition(type_name: str, encoding: str, text: str) -> dict[str, MessageDef]:
    """Every message definition in one schema, by full type name. IDL and empty schemas give
    nothing (the local search path then has to know the type)."""
    if encoding != "ros2msg" or (not text.strip() and not type_name.endswith("/Empty")):
        return {}
    out: dict[str, MessageDef] = {}
    top = normalize_name(type_name)
    sections = _SEPARATOR.split(text)
    first, rest = sections[0], sections[1:]
    if first.strip() or not rest:
        if top.split("/")[1] == "srv" and top.endswith("_Event"):
            # older bags: the raw .srv text of a service-event topic
            _add_service(out, top[: -len("_Event")], first)
        else:
            out[top] = parse_message(first, top)
    for section in rest:
        lines = section.lstrip("\n").split("\n", 1)
        m = _HEADER.match(lines[0])
        if m is None:
            continue
        kind, name = m.groups()
        body = lines[1] if len(lines) > 1 else ""
        if kind == "IDL":
            continue
        name = normalize_name(name)
        if kind == "SRV":
            _add_service(out, name, body)
        elif name not in out:
            out[name] = parse_message(body, name)
    return out


class BagTypes(Registry):
    """A registry of a bag's own definitions, falling back to the local one."""

    def __init__(self, fallback: Registry | None = None) -> None:
        super().__init__(roots=[])
        self._fallback = fallback or default_registry()
        self.known: set[str] = set()

    def add(self, type_name: str, encoding: str, text: str) -> bool:
        """Take a schema's definitions; False when they cannot be parsed."""
        try:
            defs = parse_definition(type_name, encoding, text)
        except (InterfaceError, ValueError):
            return False
        for name, mdef in defs.items():
            self._messages.setdefault(name, mdef)
            self.known.add(name)
        return normalize_name(type_name) in defs

    def message(self, name: str) -> MessageDef:
        """A definition from the bag, else from the fallback registry."""
        found = self._messages.get(name)
        if found is not None:
            return found
        full = normalize_name(name)
        found = self._messages.get(full)
        if found is not None:
            return found
        return self._fallback.message(full)


class TypeRef:
    """Base of the stand-ins `type_ref` makes: a message type known by name and hash only."""

    _TYPE_NAME: ClassVar[str] = ""
    _TYPE_HASH: ClassVar[str] = ""

    @classmethod
    def get_fields_and_field_types(cls) -> dict[str, str]:
        """Unknown here: the type has no local definition."""
        return {}


def type_ref(type_name: str, type_hash: str) -> type[TypeRef]:
    """A stand-in for a message class that only names a type and its RIHS01 hash: enough to
    publish or subscribe raw CDR bytes of a type with no local definition."""
    return type(
        type_name.rsplit("/", 1)[-1],
        (TypeRef,),
        {"_TYPE_NAME": normalize_name(type_name), "_TYPE_HASH": type_hash},
    )
