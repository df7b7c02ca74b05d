"""Rebuilding a bag's metadata.yaml from its files (`ros2 bag reindex`).

A recorder that was killed (SIGKILL, power loss) leaves MCAP files without their summary and
no metadata.yaml. Such a file is first rewritten into a complete MCAP holding every record up
to the first one that cannot be trusted (what was lost is said in one line); then
metadata.yaml is written from what the files say, keeping the custom data and distro found in
their `rosbag2` records.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path

from ros2lite.bag.errors import BagError
from ros2lite.bag.metadata import BagMetadata, write_metadata_file
from ros2lite.bag.reader import bag_files, metadata_from_files
from ros2lite.bag.storage import open_storage_reader, plugin_for
from ros2lite.bag.storage.mcap import is_complete, recover
from ros2lite.pkg.distro import ros_distro

__all__ = ["reindex"]


def reindex(
    directory: str | os.PathLike[str],
    storage_id: str | None = None,
    report: Callable[[str], object] | None = None,
) -> BagMetadata:
    """Recover unfinished MCAP files and write metadata.yaml; returns the new metadata.
    What a damaged file lost is told to `report`, one line each."""
    path = Path(directory)
    if not path.exists():
        raise BagError(f"Bag directory '{directory}' does not exist")
    if not path.is_dir():
        raise BagError("Must specify a bag directory")  # ros2cli's words for a file
    files = bag_files(path)
    if storage_id is not None:
        files = [f for f in files if plugin_for(f.name) == storage_id]
    if not files:
        raise BagError(f"No bag files (.mcap or .db3) in '{directory}'")
    sid = storage_id or plugin_for(files[0].name) or "mcap"
    summaries = []
    for f in files:
        if plugin_for(f.name) == "mcap" and not is_complete(str(f)):
            try:
                _, problems = recover(str(f))
            except OSError as e:
                raise BagError(f"Cannot rewrite '{f}': {e.strerror or e}") from None
            if report is not None:
                for line in problems:
                    report(line)
        reader = open_storage_reader(str(f), plugin_for(f.name))
        try:
            summaries.append(reader.summary())
        finally:
            reader.close()
    metadata = metadata_from_files([f.name for f in files], summaries, sid)
    if not metadata.ros_distro:
        metadata.ros_distro = ros_distro()
    try:
        write_metadata_file(path, metadata)
    except OSError as e:
        raise BagError(f"Cannot write '{path / 'metadata.yaml'}': {e.strerror or e}") from None
    return metadata
