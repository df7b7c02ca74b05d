"""Writers never follow planted symlinks, and per-user directories are checked before use."""

from __future__ import annotations

import os
import shutil
import stat
import time
from pathlib import Path

import pytest

from ros2lite.util.files import (
    UnsafePathError,
    create_new,
    open_for_writing,
    private_dir,
    replace_file,
)

DATA = Path(__file__).parent / 'bag' / 'data'


@pytest.fixture
def victim(tmp_path: Path) -> Path:
    """A file an attacker wants overwritten, outside the directory being written."""
    target = tmp_path / 'victim'
    target.write_text('precious')
    return target


def test_create_new_refuses_a_planted_symlink(tmp_path: Path, victim: Path) -> None:
    (tmp_path / 'out').symlink_to(victim)
    with pytest.raises(UnsafePathError, match='it is a symlink'):
        create_new(tmp_path / 'out')
    (tmp_path / 'dangling').symlink_to(tmp_path / 'nowhere')
    with pytest.raises(UnsafePathError):
        create_new(tmp_path / 'dangling')
    assert victim.read_text() == 'precious' and not (tmp_path / 'nowhere').exists()


def test_open_for_writing_refuses_symlinks_and_special_files(tmp_path: Path, victim: Path) -> None:
    (tmp_path / 'log').symlink_to(victim)
    for append in (False, True):
        with pytest.raises(UnsafePathError, match='symlink'):
            open_for_writing(tmp_path / 'log', append=append)
    assert victim.read_text() == 'precious'
    fd = open_for_writing(tmp_path / 'plain')
    os.write(fd, b'ok')
    os.close(fd)
    assert (tmp_path / 'plain').read_bytes() == b'ok'


def test_replace_file_replaces_the_link_not_its_target(tmp_path: Path, victim: Path) -> None:
    (tmp_path / 'metadata.yaml').symlink_to(victim)
    (tmp_path / 'metadata.yaml.tmp').symlink_to(victim)
    replace_file(tmp_path / 'metadata.yaml', 'new')
    assert victim.read_text() == 'precious'
    assert not (tmp_path / 'metadata.yaml').is_symlink()
    assert (tmp_path / 'metadata.yaml').read_text() == 'new'
    assert sorted(p.name for p in tmp_path.iterdir()) == [
        'metadata.yaml',
        'metadata.yaml.tmp',
        'victim',
    ]


def test_reindex_writes_through_no_planted_symlink(tmp_path: Path, victim: Path) -> None:
    """A killed recording (no summary) whose folder holds links at every name reindex used."""
    from ros2lite.bag.reindex import reindex
    from ros2lite.bag.writer import Writer

    bag = tmp_path / 'bag'
    w = Writer(str(bag)).open()
    tid = w.create_topic('/t', 'std_msgs/msg/String')
    for i in range(10):
        w.write_raw(tid, b'\x00\x01\x00\x00\x02\x00\x00\x00a\x00', 1000 + i, 1000 + i)
    w.flush()
    w.abandon()
    (bag / 'metadata.yaml').unlink(missing_ok=True)
    mcap = next(bag.glob('*.mcap'))
    for name in (mcap.name + '.recovering', 'metadata.yaml.tmp', 'metadata.yaml'):
        (bag / name).symlink_to(victim)
    meta = reindex(bag)
    assert meta.message_count == 10
    assert victim.read_text() == 'precious'
    assert not (bag / 'metadata.yaml').is_symlink()
    assert stat.S_IMODE(mcap.stat().st_mode) == 0o644


def _world_writable(path: Path) -> Path:
    path.mkdir()
    path.chmod(0o1777)
    return path


def test_private_dir_falls_back_from_a_shared_runtime_dir(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv('HOME', str(tmp_path / 'home'))
    shared = _world_writable(tmp_path / 'shared')
    assert private_dir(shared) == tmp_path / 'home' / '.cache' / 'ros2lite'
    assert not (shared / 'ros2lite').exists()
    mine = tmp_path / 'mine'
    mine.mkdir(mode=0o700)
    assert private_dir(mine) == mine / 'ros2lite'
    assert stat.S_IMODE((mine / 'ros2lite').stat().st_mode) == 0o700


def test_private_dir_refuses_a_planted_symlink_or_an_open_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv('HOME', str(tmp_path / 'home'))
    base = tmp_path / 'run'
    base.mkdir(mode=0o700)
    elsewhere = tmp_path / 'elsewhere'
    elsewhere.mkdir(mode=0o700)
    (base / 'ros2lite').symlink_to(elsewhere)
    assert private_dir(base) == tmp_path / 'home' / '.cache' / 'ros2lite'
    (base / 'ros2lite').unlink()
    (base / 'ros2lite').mkdir(mode=0o777)
    os.chmod(base / 'ros2lite', 0o777)
    assert private_dir(base) == base / 'ros2lite'  # ours: closed again, then used
    assert stat.S_IMODE((base / 'ros2lite').stat().st_mode) == 0o700


def test_daemon_files_leave_a_shared_runtime_dir_alone(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    """A world-writable XDG_RUNTIME_DIR with a planted log symlink: the daemon's files go to
    ~/.cache/ros2lite instead, and the log is never written through a link."""
    from ros2lite.daemon.paths import log_file, runtime_dir

    monkeypatch.setenv('HOME', str(tmp_path / 'home'))
    shared = _world_writable(tmp_path / 'shared')
    monkeypatch.setenv('XDG_RUNTIME_DIR', str(shared))
    assert runtime_dir() == tmp_path / 'home' / '.cache' / 'ros2lite'
    log = log_file('tcp/127.0.0.1:1')
    assert log.parent == runtime_dir()
    shutil.rmtree(tmp_path / 'home')


def test_read_bounded_reads_no_more_than_its_limit(tmp_path: Path) -> None:
    from ros2lite.util.files import read_bounded

    endless = tmp_path / 'package.xml'
    endless.symlink_to('/dev/zero')  # read whole, this would never end
    with pytest.raises(ValueError, match='not a regular file, so not read as a manifest'):
        read_bounded(endless, 1 << 16, ValueError, 'a manifest')
    big = tmp_path / 'big.xml'
    big.write_bytes(b'x' * ((1 << 16) + 1))
    with pytest.raises(ValueError, match='too large for a manifest'):
        read_bounded(big, 1 << 16, ValueError, 'a manifest')
    big.write_bytes(b'x' * (1 << 16))
    assert len(read_bounded(big, 1 << 16, ValueError, 'a manifest')) == 1 << 16


def test_a_fifo_is_refused_without_waiting_for_a_writer(tmp_path: Path) -> None:
    """R5-B7/R5-P1: opening a FIFO to read would block until someone writes; it is refused at
    once, as anything but a regular file is."""
    from ros2lite.util.files import ReadRefused, read_text_bounded

    fifo = tmp_path / 'params.yaml'
    os.mkfifo(fifo)
    started = time.monotonic()
    with pytest.raises(ReadRefused, match='not a regular file') as caught:
        read_text_bounded(fifo, 'a parameters file')
    assert time.monotonic() - started < 1.0
    assert caught.value.reason == 'not a regular file, so not read as a parameters file'


@pytest.mark.parametrize('target', ['/dev/zero', 'big'])
def test_param_files_from_outside_are_bounded(tmp_path: Path, target: str) -> None:
    """R5-P1: `param load` of a link to /dev/zero read 23.9 GB; every parameters file is
    now read only if it is a regular file, and at most TEXT_LIMIT bytes of it."""
    from ros2lite.parameters.files import ParamsFileError, read_params_file
    from ros2lite.util.files import TEXT_LIMIT

    link = tmp_path / 'params.yaml'
    if target == 'big':
        with open(tmp_path / 'big', 'wb') as f:
            f.truncate(TEXT_LIMIT + 4096)  # sparse: no disk used
        target = str(tmp_path / 'big')
    link.symlink_to(target)
    with pytest.raises(ParamsFileError) as caught:
        read_params_file(link)
    message = str(caught.value)
    assert message.startswith(f"Couldn't read parameters file '{link}': "), message
    assert ('not a regular file' in message) == (target == '/dev/zero'), message
    assert '\n' not in message
