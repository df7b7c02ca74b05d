"""What a router's admin space tells about the sessions connected to it.

The router publishes ``@/<zid>/router`` (JSON with one entry per connected session: its zid
and whether it is a peer, client or router) when its ``adminspace`` is enabled, as the
ros2lite daemon's is.  Node names come from the rmw_zenoh liveliness tokens of those zids.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field

import zenoh

from ros2lite.transport.handles import Session
from ros2lite.transport.keys import EntityKind, parse_token
from ros2lite.transport.session import as_zenoh

__all__ = ["ConnectedSession", "router_sessions"]

LIVELINESS_ALL = "@ros2_lv/**"


@dataclass(frozen=True)
class ConnectedSession:
    """One session linked to the router, with the ROS nodes it runs (where known)."""

    zid: str
    whatami: str  # "peer", "client" or "router"
    nodes: list[str] = field(default_factory=list)  # "/ns/name", with " (domain N)" if foreign


def _router_info(session: Session, router_zid: str, timeout: float) -> dict[str, object] | None:
    replies = as_zenoh(session).get(
        f"@/{router_zid}/router", zenoh.handlers.FifoChannel(16), timeout=timeout
    )
    for reply in replies:
        if reply.ok is None:
            continue
        try:
            data = json.loads(reply.ok.payload.to_bytes())
        except ValueError:
            continue
        if isinstance(data, dict):
            return data
    return None


def _node_names(session: Session, domain_id: int, timeout: float) -> dict[str, list[str]]:
    names: dict[str, list[str]] = {}
    replies = (
        as_zenoh(session)
        .liveliness()
        .get(LIVELINESS_ALL, zenoh.handlers.FifoChannel(1 << 16), timeout=timeout)
    )
    for reply in replies:
        if reply.ok is None:
            continue
        entity = parse_token(str(reply.ok.key_expr))
        if entity is None or entity.kind != EntityKind.NODE:
            continue
        name = entity.namespace.rstrip("/") + "/" + entity.node_name
        if entity.domain_id != domain_id:
            name += f" (domain {entity.domain_id})"
        names.setdefault(entity.zid, []).append(name)
    return {zid: sorted(found) for zid, found in names.items()}


def router_sessions(
    session: Session, domain_id: int, timeout: float = 2.0
) -> list[ConnectedSession] | None:
    """The sessions (other than ``session`` itself) linked to the router ``session`` is
    connected to; None when there is no router or its admin space does not answer."""
    routers = session.info.routers_zid()
    if not routers:
        return None
    info = _router_info(session, str(routers[0]), timeout)
    if info is None:
        return None
    own = str(session.zid())
    names = _node_names(session, domain_id, timeout)
    out = []
    sessions = info.get("sessions", [])
    for entry in sessions if isinstance(sessions, list) else []:
        if not isinstance(entry, dict):
            continue  # the admin space is outside data: skip what is not a session entry
        zid = str(entry.get("peer", ""))
        if not zid or zid == own:
            continue
        out.append(ConnectedSession(zid, str(entry.get("whatami", "?")), names.get(zid, [])))
    out.sort(key=lambda s: (s.whatami, s.nodes, s.zid))
    return out
