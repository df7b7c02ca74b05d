"""How `daemon status` and `daemon stop` describe the sessions connected to the router."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol


class Session(Protocol):
    """What is shown of a session connected to the router (the daemon's ConnectedSession)."""

    @property
    def zid(self) -> str:
        """The session's Zenoh id."""
        ...

    @property
    def whatami(self) -> str:
        """'peer', 'client' or 'router'."""
        ...

    @property
    def nodes(self) -> list[str]:
        """The ROS nodes it runs, by full name."""
        ...


def _plural(n: int, word: str) -> str:
    return f"{n} {word}" + ("" if n == 1 else "s")


def table(sessions: Sequence[Session]) -> list[str]:
    """`Connected sessions: N`, then one line per session: mode, zid, its nodes."""
    lines = [f"Connected sessions: {len(sessions)}"]
    for s in sessions:
        lines.append(f"  {s.whatami:<6}  {s.zid:<32}  {', '.join(s.nodes) or '(no nodes)'}")
    return lines


def consequences(sessions: Sequence[Session]) -> list[str]:
    """What stopping the router did to the sessions that were connected to it."""
    if not sessions:
        return []
    peers = len([s for s in sessions if s.whatami == "peer"])
    others = len(sessions) - peers
    nodes = sorted(n for s in sessions for n in s.nodes)
    were = "was" if len(sessions) == 1 else "were"
    lines = [
        f"{_plural(len(sessions), 'session')} {were} connected to it"
        + (f" (nodes: {', '.join(nodes)})" if nodes else "")
    ]
    if peers:
        keep, they = ("keeps", "it knows") if peers == 1 else ("keep", "they know")
        lines.append(
            f"{_plural(peers, 'peer session')} {keep} exchanging data with the peers "
            f"{they} already; nodes started from now on are not discovered until "
            "a router runs again ('ros2lite daemon start')"
        )
    if others:
        lines.append(
            f"{_plural(others, 'client session')} (CLI verbs, client-mode nodes) "
            "lost the connection until a router runs again"
        )
    return lines
