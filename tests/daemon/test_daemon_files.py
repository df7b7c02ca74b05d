"""The daemon's log, pid and lock files are never written through a planted symlink."""

from __future__ import annotations

from pathlib import Path

import pytest

from ros2lite import daemon
from ros2lite.daemon.errors import DaemonError
from ros2lite.daemon.paths import log_file


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


def test_the_package_hands_on_names_its_modules_define() -> None:
    # ros2lite.daemon loads its names lazily from the module of the package that defines
    # each (control, errors, paths, probe, router); each must be there, and be that one
    import importlib

    for name in daemon.__all__:
        value = getattr(daemon, name)
        home = importlib.import_module(value.__module__)
        assert home.__name__.startswith("ros2lite.daemon.") and getattr(home, name) is value
