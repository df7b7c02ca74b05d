"""The bag verbs' shared options agree with the library they front."""

from __future__ import annotations

from ros2lite.bag.storage import PLUGINS
from ros2lite.cli.bag.options import STORAGE_IDS


def test_storage_ids_are_the_plugins() -> None:
    # written out in the CLI so that parsing imports no bag code; a plugin added to the
    # library must be offered by -s/--storage too
    assert list(STORAGE_IDS) == list(PLUGINS)
