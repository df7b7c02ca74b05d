"""The daemon's log, pid and lock files are never written through a planted symlink."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite import daemon
from ros2lite.daemon.router import DaemonError, log_file


def test_a_planted_log_symlink_is_refused(endpoint: str, runtime: Path, tmp_path: Path) -> None:
    victim = tmp_path / 'victim'
    victim.write_text('precious')
    log = log_file(endpoint)
    log.symlink_to(victim)
    with pytest.raises(DaemonError):
        daemon.start(endpoint, timeout=10)
    assert victim.read_text() == 'precious'
    log.unlink()
    assert daemon.start(endpoint).started  # with the link gone it starts
    assert not log.is_symlink() and daemon.stop(endpoint).stopped


def test_the_package_hands_on_names_the_router_module_defines() -> None:
    # ros2lite.daemon loads its names lazily from the router module (the runtime dir from
    # the paths module); each must be there
    from ros2lite.daemon import paths, router

    for name in daemon.__all__:
        assert getattr(daemon, name) is getattr(paths if name == "runtime_dir" else router, name)
