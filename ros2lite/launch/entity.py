"""The launch description entity: anything a launch description holds.

Visiting an entity (the launch service does it, depth first, in order) may return more
entities to visit right away: that is how a group, an include or a launch description
unfolds. Actions (:mod:`.actions`), event handlers and the service all speak of entities, so
the base stands below all of them; :mod:`.actions` offers it too. (Not to be confused with
:mod:`.frontend.entity`, an element of an XML or YAML launch file.)
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .context import LaunchContext

__all__ = ['Entities', 'LaunchDescriptionEntity']

Entities = list['LaunchDescriptionEntity']


class LaunchDescriptionEntity:
    """Anything a launch description holds."""

    def visit(self, context: LaunchContext) -> Entities | None:
        """Do this entity's work; return entities to visit next."""
        return None

    def describe(self) -> str:
        """A short name for listings (`launch -p`)."""
        return type(self).__name__

    def describe_sub_entities(self) -> list[LaunchDescriptionEntity]:
        """Entities always reached through this one (for introspection)."""
        return []

    def describe_conditional_sub_entities(
        self,
    ) -> list[tuple[str, list[LaunchDescriptionEntity]]]:
        """Entities reached only if something happens (a timer, an event)."""
        return []
