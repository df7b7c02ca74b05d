"""Where interface definitions come from, and the cache of parsed definitions.

Packages come from the package index (:mod:`ros2lite.pkg.index`), first source first:
``ROS2LITE_INTERFACE_PATH`` directories holding ``<pkg>/msg|srv|action``, source workspaces
(a package's own ``msg/ srv/ action/``), ``share/<pkg>`` of every ``AMENT_PREFIX_PATH``
prefix, then the bundled ``ros2lite/msgs``. A whole package comes from one place so a user's
copy of a package never mixes with ours.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path
from typing import TypeVar

from ros2lite.pkg.distro import ros_distro
from ros2lite.pkg.index import BUNDLED_INTERFACES, PackageIndex, interface_packages
from ros2lite.util.files import read_text_bounded

from .errors import InterfaceError, UnknownInterfaceError
from .parser import (
    ActionDef,
    Field,
    FieldType,
    MessageDef,
    ServiceDef,
    parse_action,
    parse_message,
    parse_service,
    validate_type_name,
)

BUNDLED = BUNDLED_INTERFACES
KINDS = ('msg', 'srv', 'action')
EXTENSIONS = {'msg': '.msg', 'srv': '.srv', 'action': '.action'}

# Generated action sub-types, longest suffix first so '_SendGoal_Request' beats '_Request'.
ACTION_SUFFIXES = (
    '_SendGoal_Request',
    '_SendGoal_Response',
    '_SendGoal_Event',
    '_GetResult_Request',
    '_GetResult_Response',
    '_GetResult_Event',
    '_FeedbackMessage',
    '_SendGoal',
    '_GetResult',
    '_Goal',
    '_Result',
    '_Feedback',
)
SERVICE_SUFFIXES = ('_Request', '_Response', '_Event')

_UUID = FieldType('unique_identifier_msgs/msg/UUID')
_TIME = FieldType('builtin_interfaces/msg/Time')
_EVENT_INFO = FieldType('service_msgs/msg/ServiceEventInfo')


# the largest upstream definition is a few KB; past this a file is no definition
DEFINITION_LIMIT = 1024 * 1024


def read_definition(path: Path) -> str:
    """A definition file's text, read only if it is a regular file of at most
    DEFINITION_LIMIT bytes of UTF-8 (a link to /dev/zero is one InterfaceError)."""
    return read_text_bounded(path, 'an interface definition', DEFINITION_LIMIT, InterfaceError)


_Def = TypeVar('_Def')
_warned: set[str] = set()


def _warn_once(text: str) -> None:
    """One line on stderr, as a logger's warning reads (the logging module sits above the
    type system: it publishes /rosout messages)."""
    if text not in _warned:
        _warned.add(text)
        print(f'[WARN] [ros2lite.interfaces]: {text}', file=sys.stderr, flush=True)


def _is_interface_package(path: Path) -> bool:
    return any((path / kind).is_dir() for kind in KINDS)


class Registry:
    """Finds, parses and caches definitions; one per search path configuration."""

    def __init__(self, roots: list[Path] | None = None) -> None:
        # explicit roots (directories of packages) replace the package index
        self.roots = roots
        self._packages: dict[str, Path] | None = None
        self._messages: dict[str, MessageDef] = {}
        self._services: dict[str, ServiceDef] = {}
        self._actions: dict[str, ActionDef] = {}
        # definitions that came from elsewhere than a file (a node's type description, see
        # interfaces/remote.py): 'pkg/kind/Name' → (where from, text); consulted first
        self._given: dict[str, tuple[str, str]] = {}

    # -- discovery -------------------------------------------------------------------------
    def packages(self) -> dict[str, Path]:
        """Package name → its directory (the one holding msg/srv/action)."""
        if self._packages is None and self.roots is None:
            self._packages = interface_packages()
        if self._packages is None:
            found: dict[str, Path] = {}
            for root in self.roots or ():
                try:
                    children = sorted(root.iterdir())
                except OSError:
                    continue
                for child in children:
                    if child.name not in found and _is_interface_package(child):
                        found[child.name] = child
            self._packages = found
        return self._packages

    def package_dir(self, package: str) -> Path:
        """The directory of a package (UnknownInterfaceError if none)."""
        try:
            return self.packages()[package]
        except KeyError:
            # with the package index's search path, say why when it is shown
            explain = (lambda: PackageIndex().why_missing(package)) if self.roots is None else None
            raise UnknownInterfaceError(f"Unknown package '{package}'", explain) from None

    def package_interfaces(self, package: str) -> list[str]:
        """Sorted 'pkg/kind/Name' of every definition file in a package."""
        base = self.package_dir(package)
        names = []
        for kind in KINDS:
            d = base / kind
            if d.is_dir():
                names += [f'{package}/{kind}/{p.stem}' for p in d.glob('*' + EXTENSIONS[kind])]
        return sorted(names)

    def all_interfaces(self) -> list[str]:
        """Every 'pkg/kind/Name' on the search path, by package."""
        return [n for pkg in sorted(self.packages()) for n in self.package_interfaces(pkg)]

    def interface_path(self, name: str) -> Path:
        """The file defining 'pkg/kind/Name' (no generated sub-types); for a bundled package,
        the current distribution's own definition where it changed after Jazzy."""
        pkg, kind, short = validate_type_name(name)
        base = self.package_dir(pkg)
        path = base / kind / (short + EXTENSIONS[kind])
        if base.parent == BUNDLED:
            changed = BUNDLED / f'_{ros_distro()}' / pkg / kind / path.name
            if changed.is_file():
                return changed
        if not path.is_file():
            if path.is_symlink() or path.exists():  # there, but no file to read (R5-I1)
                raise InterfaceError(
                    f'{path}: not a regular file, so not read as an interface definition'
                )
            raise UnknownInterfaceError(f"Unknown interface '{name}'")
        return path

    def interface_text(self, name: str) -> str:
        """The definition file's text."""
        return self.interface_source(name)[1]

    def interface_source(self, name: str) -> tuple[str, str]:
        """Where the definition of 'pkg/kind/Name' comes from (a path, or a node) and its
        text."""
        given = self._given.get(name)
        if given is not None:
            return given
        path = self.interface_path(name)
        return str(path), read_definition(path)

    def add_definitions(
        self, texts: dict[str, str], messages: dict[str, MessageDef], origin: str
    ) -> None:
        """Take definitions that no file holds: texts of 'pkg/kind/Name' interfaces and
        parsed generated sub-types (a node's type description); names known already stay."""
        for name, text in texts.items():
            if not self.exists(name):
                self._given[name] = (origin, text)
        for name, mdef in messages.items():
            self._messages.setdefault(name, mdef)

    def exists(self, name: str) -> bool:
        """Whether a definition file for 'pkg/kind/Name' exists."""
        if name in self._given:
            return True
        try:
            self.interface_path(name)
        except InterfaceError:
            return False
        return True

    # -- definitions -----------------------------------------------------------------------
    def _parsed(self, name: str, parse: Callable[[str, str, str], _Def]) -> _Def:
        """`parse` of the definition of `name`; when the file the index found does not
        read or parse (a broken file in an installed wheel, R5-I1) and ros2lite bundles that
        interface, the bundled definition, with one warning naming the broken file."""
        given = self._given.get(name)
        if given is not None:
            return parse(given[1], name, given[0])
        pkg, kind, short = validate_type_name(name)
        path = self.package_dir(pkg) / kind / (short + EXTENSIONS[kind])
        try:
            path = self.interface_path(name)
            return parse(read_definition(path), name, str(path))
        except UnknownInterfaceError:
            raise
        except InterfaceError as e:
            bundled = BUNDLED / pkg / kind / path.name
            if BUNDLED in path.parents or not bundled.is_file():
                raise
            _warn_once(f'{e}; using the definition ros2lite bundles for {name}')
            return parse(read_definition(bundled), name, str(bundled))

    def service(self, name: str) -> ServiceDef:
        """The parsed definition of a service (cached)."""
        svc = self._services.get(name)
        if svc is None:
            svc = self._services[name] = self._parsed(name, parse_service)
        return svc

    def action(self, name: str) -> ActionDef:
        """The parsed definition of an action (cached)."""
        act = self._actions.get(name)
        if act is None:
            act = self._actions[name] = self._parsed(name, parse_action)
        return act

    def message(self, name: str) -> MessageDef:
        """Definition of any message-like type, including generated service/action parts."""
        msg = self._messages.get(name)
        if msg is None:
            msg = self._load_message(normalize_name(name))
            self._messages[name] = msg
        return msg

    def _load_message(self, name: str) -> MessageDef:
        _, kind, short = validate_type_name(name)
        if kind == 'msg':
            return self._parsed(name, parse_message)
        if kind == 'srv':
            for suffix in SERVICE_SUFFIXES:
                if short.endswith(suffix) and self.exists(name[: -len(suffix)]):
                    svc = self.service(name[: -len(suffix)])
                    if suffix == '_Request':
                        return svc.request
                    if suffix == '_Response':
                        return svc.response
                    return event_message(svc.name, svc.request.name, svc.response.name)
            raise UnknownInterfaceError(f"Unknown interface '{name}'")
        for suffix in ACTION_SUFFIXES:
            if short.endswith(suffix) and self.exists(name[: -len(suffix)]):
                return action_part(self.action(name[: -len(suffix)]), suffix)
        raise UnknownInterfaceError(f"Unknown interface '{name}'")

    def kind_of(self, name: str) -> str:
        """'message', 'service' or 'action' for a type name (services/actions are files)."""
        name = normalize_name(name)
        _, kind, _ = validate_type_name(name)
        if kind == 'srv' and self.exists(name):
            return 'service'
        if kind == 'action' and self.exists(name):
            return 'action'
        if kind == 'action' and any(name.endswith(s) for s in ('_SendGoal', '_GetResult')):
            return 'service'
        self.message(name)  # raises for unknown names
        return 'message'


def normalize_name(name: str) -> str:
    """Accept 'pkg/Name' as shorthand for 'pkg/msg/Name'."""
    parts = name.split('/')
    if len(parts) == 2:
        return f'{parts[0]}/msg/{parts[1]}'
    return name


def event_message(service: str, request: str, response: str) -> MessageDef:
    """The `<S>_Event` message rosidl generates for service introspection."""
    return MessageDef(
        service + '_Event',
        [
            Field('info', _EVENT_INFO),
            Field('request', FieldType(request, 0, 'bounded', 1)),
            Field('response', FieldType(response, 0, 'bounded', 1)),
        ],
    )


def action_part(action: ActionDef, suffix: str) -> MessageDef:
    """One of the messages generated for an action, by its name suffix."""
    n = action.name
    parts: dict[str, MessageDef] = {
        '_Goal': action.goal,
        '_Result': action.result,
        '_Feedback': action.feedback,
        '_SendGoal_Request': MessageDef(
            n + '_SendGoal_Request',
            [Field('goal_id', _UUID), Field('goal', FieldType(n + '_Goal'))],
        ),
        '_SendGoal_Response': MessageDef(
            n + '_SendGoal_Response', [Field('accepted', FieldType('bool')), Field('stamp', _TIME)]
        ),
        '_GetResult_Request': MessageDef(n + '_GetResult_Request', [Field('goal_id', _UUID)]),
        '_GetResult_Response': MessageDef(
            n + '_GetResult_Response',
            [Field('status', FieldType('int8')), Field('result', FieldType(n + '_Result'))],
        ),
        '_FeedbackMessage': MessageDef(
            n + '_FeedbackMessage',
            [Field('goal_id', _UUID), Field('feedback', FieldType(n + '_Feedback'))],
        ),
        '_SendGoal_Event': event_message(
            n + '_SendGoal', n + '_SendGoal_Request', n + '_SendGoal_Response'
        ),
        '_GetResult_Event': event_message(
            n + '_GetResult', n + '_GetResult_Request', n + '_GetResult_Response'
        ),
    }
    if suffix not in parts:
        raise UnknownInterfaceError(f"'{n}{suffix}' is a service, not a message")
    return parts[suffix]


_DEFAULT: Registry | None = None


def default_registry() -> Registry:
    """The process-wide registry; the search path is read from the environment once."""
    global _DEFAULT
    reg = _DEFAULT
    if reg is None:
        reg = _DEFAULT = Registry()
    return reg


def reload_registry(registry: Registry | None = None) -> Registry:
    """Re-read the package index (new classes are built afresh), or put `registry` back (a
    test that changed the search path for a while: classes made before stay the ones used)."""
    global _DEFAULT
    _DEFAULT = Registry() if registry is None else registry
    return _DEFAULT
