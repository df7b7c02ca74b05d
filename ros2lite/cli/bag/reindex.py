"""`bag reindex`: rebuild metadata.yaml (and unfinished MCAP files) from the bag's files."""

from __future__ import annotations

from ..parsing import command
from .options import bag_argument, bag_error, warn


@command("reindex")
@bag_argument
def cli(bag_path: str, storage: str | None) -> None:
    """Reconstruct metadata file for a bag."""
    from ros2lite.bag.errors import BagError
    from ros2lite.bag.reindex import reindex

    try:
        reindex(bag_path, storage, report=warn)
    except BagError as e:
        raise bag_error(str(e)) from None
