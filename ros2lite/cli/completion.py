"""Shell completion of names: topics and nodes from the live graph, types and packages from
the local index.

Completion runs on every Tab press, so it must be quick and quiet: it never starts the
daemon, waits at most about a second for the graph, and any failure simply completes
nothing. Enable with `eval "$(_ROS2LITE_COMPLETE=bash_source ros2lite)"` (zsh_source and
fish_source work too).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING

import click
from click.shell_completion import CompletionItem

if TYPE_CHECKING:
    from ros2lite.graph import Entity

_GRAPH_TIMEOUT = 1.0

Completer = Callable[[click.Context, click.Parameter, str], list[CompletionItem]]


def _matching(names: Iterable[str], incomplete: str) -> list[CompletionItem]:
    return [CompletionItem(n) for n in sorted(set(names)) if n.startswith(incomplete)]


def _quietly(fn: Callable[[click.Context, str], list[CompletionItem]]) -> Completer:
    """A completer that completes nothing instead of failing: a traceback in the middle of
    the user's command line is worse than no suggestions."""

    def complete(
        ctx: click.Context, _param: click.Parameter, incomplete: str
    ) -> list[CompletionItem]:
        try:
            return fn(ctx, incomplete)
        except Exception:
            return []

    return complete


def _graph_entities(ctx: click.Context) -> list[Entity]:
    """The domain's entities if a router answers now; [] otherwise (no daemon start)."""
    from ros2lite.tools.connection import Connection

    # a `--router` typed on the line being completed counts (no group callback runs here)
    router = ctx.find_root().params.get('router')
    with Connection(router=router, autostart=False) as conn:
        return conn.entities(timeout=_GRAPH_TIMEOUT)


def _hidden_wanted(incomplete: str) -> bool:
    # hidden names show up once the user has typed into one ("/_…" or "…/_…")
    return '/_' in incomplete or incomplete.startswith('_')


def _graph_names(kind: str) -> Completer:
    """The names of the graph's topics, services or actions (`kind`)."""

    @_quietly
    def complete(ctx: click.Context, incomplete: str) -> list[CompletionItem]:
        from ros2lite.graph import (
            action_names_and_types,
            service_names_and_types,
            topic_names_and_types,
        )

        names_and_types = {
            'topic': topic_names_and_types,
            'service': service_names_and_types,
            'action': action_names_and_types,
        }[kind]
        names = names_and_types(_graph_entities(ctx), _hidden_wanted(incomplete))
        return _matching((name for name, _ in names), incomplete)

    return complete


topics = _graph_names('topic')
services = _graph_names('service')
actions = _graph_names('action')


@_quietly
def nodes(ctx: click.Context, incomplete: str) -> list[CompletionItem]:
    from ros2lite.graph import node_full_names

    entities = _graph_entities(ctx)
    return _matching(node_full_names(entities, _hidden_wanted(incomplete)), incomplete)


def _interfaces(kind: str | None, incomplete: str) -> list[CompletionItem]:
    from ros2lite.interfaces.registry import default_registry

    names = default_registry().all_interfaces()
    if kind is not None:
        names = [n for n in names if n.split('/')[1] == kind]
    return _matching(names, incomplete)


@_quietly
def message_types(_ctx: click.Context, incomplete: str) -> list[CompletionItem]:
    return _interfaces('msg', incomplete)


@_quietly
def service_types(_ctx: click.Context, incomplete: str) -> list[CompletionItem]:
    return _interfaces('srv', incomplete)


@_quietly
def action_types(_ctx: click.Context, incomplete: str) -> list[CompletionItem]:
    return _interfaces('action', incomplete)


@_quietly
def interface_types(_ctx: click.Context, incomplete: str) -> list[CompletionItem]:
    return _interfaces(None, incomplete)


@_quietly
def interface_packages(_ctx: click.Context, incomplete: str) -> list[CompletionItem]:
    from ros2lite.interfaces.registry import default_registry

    return _matching(default_registry().packages(), incomplete)


@_quietly
def executable_packages(_ctx: click.Context, incomplete: str) -> list[CompletionItem]:
    from ros2lite.pkg.executables import list_packages

    return _matching(list_packages(), incomplete)


@_quietly
def executables(ctx: click.Context, incomplete: str) -> list[CompletionItem]:
    from ros2lite.pkg.executables import get_executables

    package = ctx.params.get('package_name')
    if not package:
        return []
    return _matching((e.name for e in get_executables(package)), incomplete)


@_quietly
def launch_files(ctx: click.Context, incomplete: str) -> list[CompletionItem]:
    from ros2lite.launch.api import launch_files as files

    package = ctx.params.get('package_name')
    if not package:
        return []
    return _matching(files(package), incomplete)
