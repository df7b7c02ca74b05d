from __future__ import annotations

from tests.action.alien import alien_server
from tests.action.fixtures import fx

__all__ = ['alien_server', 'fx']
