"""An alien (bare zenoh) Fibonacci action server for the action verbs to talk to."""

from __future__ import annotations

from tests.action.alien import alien_server

__all__ = ['alien_server']
