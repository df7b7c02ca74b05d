"""`component` verbs against a container that is not ros2lite (a bare zenoh stand-in that
answers as rclcpp_components' container would): the wire format is the contract."""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator
from typing import Any

import pytest

from tests.cli.component.alien_container import AlienContainer, LoadRequest
from tests.cli.conftest import Result
from tests.spinning import wait_until

Run = Callable[..., Result]


@pytest.fixture
def alien(alien_session: Any) -> Iterator[AlienContainer]:
    container = AlienContainer(alien_session, int(os.environ['ROS_DOMAIN_ID']))
    try:
        yield container
    finally:
        container.close()


def test_drive_an_alien_container(run: Run, alien: AlienContainer) -> None:
    wait_until(lambda: '/alien_container' in run('component', 'list', '--containers-only').out)
    assert run('component', 'list', '/alien_container').out == ''
    loaded = run(
        'component', 'load', '/alien_container', 'alien_pkg', 'alien_pkg::Widget',
        '-n', 'w1', '--node-namespace', '/alien_ns', '--log-level', 'DEBUG',
        '-r', 'chatter:=other', '-p', 'speed:=2.5', '-p', 'label:=fast',
        '-e', 'use_intra_process_comms:=true',
    )  # fmt: skip
    assert (loaded.code, loaded.out) == (
        0,
        "Loaded component 1 into '/alien_container' container node as '/alien_ns/w1'\n",
    )
    # the request as the container decoded it, field by field
    assert alien.requests[0] == LoadRequest(
        'alien_pkg',
        'alien_pkg::Widget',
        'w1',
        '/alien_ns',
        10,
        ['chatter:=other'],
        [('speed', 2.5), ('label', 'fast')],
        [('use_intra_process_comms', True)],
    )
    assert (
        run('component', 'load', '-q', '/alien_container', 'alien_pkg', 'alien_pkg::Widget').out
        == '2\n'
    )
    wait_until(lambda: '/alien_ns/w1' in run('node', 'list').out)
    assert run('component', 'list', '/alien_container').out == '1  /alien_ns/w1\n2  /widget\n'
    assert run('component', 'unload', '/alien_container', '1').out == (
        "Unloaded component 1 from '/alien_container' container node\n"
    )
    wait_until(lambda: '/alien_ns/w1' not in run('node', 'list').out)
    refused = run('component', 'unload', '/alien_container', '7')
    assert (refused.code, refused.err) == (
        1,
        "Failed to unload component 7 from '/alien_container' container node\n"
        '    No node found with unique_id: 7\n',
    )
    unknown = run('component', 'load', '/alien_container', 'other_pkg', 'other_pkg::X')
    assert (unknown.code, unknown.err) == (
        1,
        'Failed to load component: Could not find requested resource in ament index\n',
    )
    bad_level = run(
        'component',
        'load',
        '/alien_container',
        'alien_pkg',
        'alien_pkg::Widget',
        '--log-level',
        'LOUD',
    )
    assert bad_level.code == 1 and "Invalid log level 'LOUD'" in bad_level.err
