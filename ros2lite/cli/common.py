"""Pieces every graph verb shares: connecting (the library's Connection: daemon auto-start,
the hidden CLI node, graph snapshots, spinning), names given by the user and found in the
graph, and field values given in YAML. The shared options are in `options`, the shared
printers in `render`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import click

from . import render
from .errors import CliError

if TYPE_CHECKING:
    from ros2lite.graph import Entity
    from ros2lite.interfaces import Message
    from ros2lite.node import Node
    from ros2lite.tools.connection import Connection


def yaml_fields(values: str, *, allow_empty: bool = False) -> dict[str, object]:
    """The field values given in YAML (VALUES or --stdin) as a mapping, or ros2cli's line
    saying why they are not one, with the line and column where YAML breaks (`allow_empty`:
    empty text means no fields, as in `service call`). A JSON object is read as JSON (YAML
    1.1 would take `1e-07` for a string), so `--json` output comes back exactly."""
    from ros2lite.util.safe_yaml import YamlInputError, load

    obj = json_object(values)
    if obj is not None:
        return obj

    try:
        parsed = load(values, 'the passed value')
    except YamlInputError as e:
        if not e.syntax:
            raise CliError(str(e)) from None
        # ros2cli's line, and where the YAML breaks (as `param load` says it)
        raise CliError(
            f'The passed value needs to be in YAML string or a dictionary: {e.detail}'
        ) from None
    if parsed is None and allow_empty:
        return {}
    if not isinstance(parsed, dict):
        raise CliError('The passed value needs to be a dictionary in YAML format')
    return parsed


def json_object(text: str) -> dict[str, object] | None:
    """`text` read as a JSON object, or None when it is not one (YAML then reads it: a flow
    mapping, or broken text YAML says where)."""
    import json

    if not text.lstrip().startswith('{'):
        return None
    try:
        obj = json.loads(text)
    except ValueError:
        return None
    return obj if isinstance(obj, dict) else None


def message_fields(cls: type[Message], fields: dict[str, object]) -> dict[str, object]:
    """`fields` with the JSON form's spellings (base64 byte arrays, "nan"/"inf") turned into
    values, so `--json` output fills a message; YAML never means anything else by them (a
    string for an array or a float is an error there)."""
    from ros2lite.interfaces.json_form import json_to_fields

    return json_to_fields(cls, fields)


def connect(
    *,
    no_daemon: bool = False,
    use_sim_time: bool = False,
    as_node: bool = False,
    autostart: bool | None = None,
) -> Connection:
    """This run's connection to the graph (the daemon's graph cache asked, and the daemon
    started on demand unless `--no-daemon` or `autostart` is false; a node's peer session
    with `as_node`); use it as a context manager."""
    from ros2lite.tools.connection import Connection

    return Connection(
        autostart=not no_daemon if autostart is None else autostart,
        use_sim_time=use_sim_time,
        as_node=as_node,
        graph_cache=not no_daemon,
        on_note=lambda text: render.echo(f'ros2lite: {text}', err=True),
    )


def known_type(conn: Connection, type_name: str, name: str | None = None) -> None:
    """When no local package defines `type_name`, fetch it from a node that uses it (on topic
    or service `name` first): then the verb sees it as any local type. One line on stderr
    says where it came from; a description that does not fit is the verb's one error line."""
    from ros2lite.remote_types import ensure_type

    ensure_type(conn.node, conn.entities(), type_name, name, say=lambda t: render.echo(t, err=True))


def known_type_if_graph(type_name: str, name: str | None = None) -> None:
    """`known_type` for a verb that needs no graph otherwise (`interface show`, the type
    check of `service call`): no daemon is started for it, and no router means no fetch
    (the verb then says the type is unknown, as it would have)."""
    from ros2lite.exceptions import Ros2liteError
    from ros2lite.remote_types import RemoteTypeError, is_known

    if len(type_name.split('/')) != 3 or is_known(type_name):
        return
    try:
        with connect(autostart=False) as conn:
            known_type(conn, type_name, name)
    except RemoteTypeError:
        raise
    except Ros2liteError:
        return


def resolved_name(node: Node, name: str, kind: str) -> str:
    """`name` resolved by the CLI's node as a `kind` ('service', 'action') name, or ros2cli's
    line saying it is invalid."""
    resolve = node.resolve_service_name if kind == 'service' else node.resolve_topic_name
    try:
        return resolve(name)
    except ValueError:
        raise CliError(f"The {kind} name '{name}' is invalid") from None


def interface_type_name(name: str, kind: str, *, invalid: str, not_kind: str | None = None) -> str:
    """A user-given 'pkg/Name' or 'pkg/<kind>/Name' as the full name of an existing
    interface of that kind; ros2cli's messages (`invalid`, `not_kind`) otherwise."""
    from ros2lite.interfaces import InterfaceError, get_interface

    parts = name.split('/')
    if len(parts) == 2:
        parts = [parts[0], kind, parts[1]]
    if len(parts) != 3 or not all(parts):
        raise CliError(invalid)
    full = '/'.join(parts)
    try:
        get_interface(full)
    except (InterfaceError, ValueError, LookupError):
        raise CliError(invalid) from None
    if parts[1] != kind:
        raise CliError(not_kind or invalid)
    return full


def print_names_of_type(
    type_name: str,
    count: bool,
    no_daemon: bool,
    names_and_types: Callable[[list[Entity]], list[tuple[str, list[str]]]],
    as_json: bool = False,
) -> None:
    """What `topic/service/action find` share: the names in the graph with `type_name`
    among their types, one a line, or only how many (`count`)."""
    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    render.print_names(
        [(name, types) for name, types in names_and_types(entities) if type_name in types],
        count,
        types=False,
        as_json=as_json,
    )


def print_types_of(
    name: str,
    no_daemon: bool,
    names_and_types: Callable[[list[Entity]], list[tuple[str, list[str]]]],
    kind: str = 'topic',
    as_json: bool = False,
) -> None:
    """What `topic/service/action type` share: the type(s) of `name` in the graph. Exit 1 as
    ros2cli does when there is none, with nothing on stdout (scripts read it) and one line
    on stderr saying why (ros2cli says nothing at all)."""
    from ros2lite.names import expand_topic_name

    try:
        full = expand_topic_name(name, 'ros2lite', '/', is_service=kind == 'service')
    except ValueError as e:
        raise CliError(str(e).replace('topic name', f'{kind} name', 1)) from None
    with connect(no_daemon=no_daemon) as conn:
        entities = conn.entities()
    types = dict(names_and_types(entities)).get(full)
    if types is None:
        raise CliError(f"Unknown {kind} '{full}' (not in the graph now)")
    if as_json:
        render.print_json({'name': full, 'types': types})
    else:
        render.echo('\n'.join(types))


def wait_saying_other_types(
    ready: Callable[[float], bool],
    timeout: float | None,
    kind: str,
    name: str,
    type_name: str,
    served_types: Callable[[], list[tuple[str, list[str]]]],
) -> bool:
    """Wait up to `timeout` s (None: for ever) until `ready(step)` holds, saying once on
    stderr when `name` is served with another type than `type_name` (such a wait would
    otherwise go on in silence, as ros2cli's does). True when ready."""
    import time

    deadline = None if timeout is None else time.monotonic() + timeout
    warned = False
    while True:
        left = None if deadline is None else max(0.0, deadline - time.monotonic())
        if ready(0.5 if left is None else min(0.5, left)):
            return True
        if not warned:
            others = sorted(
                {t for n, types in served_types() if n == name for t in types if t != type_name}
            )
            if others:
                from ros2lite.pkg.distro import other_distro_name

                warned = True
                hint = other_distro_name(type_name, others)
                click.echo(
                    f"WARNING: {kind} '{name}' is served as {', '.join(others)}, not "
                    f'{type_name}; nothing will answer until a server of {type_name} appears'
                    + (f' ({hint})' if hint else ''),
                    err=True,
                )
        if deadline is not None and time.monotonic() >= deadline:
            return False


def plot_request(
    series: tuple[str, ...] | list[str],
    xy: bool,
    snapshot: bool,
    pictures: tuple[str | None, ...],
    csv_out: bool,
) -> tuple[list[str], list[str]]:
    """What `topic plot` and `bag plot` were asked for, checked alike: the series (each an
    absolute name) and the picture files to write; one line when the options clash."""
    if xy and snapshot:
        raise CliError('--xy and --snapshot are two kinds of plot: choose one')
    files = [p for p in pictures if p]
    if csv_out and files:
        raise CliError('--csv prints the samples instead of a picture: give one or the other')
    return [t if t.startswith('/') else '/' + t for t in series], files
