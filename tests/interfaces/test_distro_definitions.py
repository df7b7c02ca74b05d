"""Definitions a later distribution changed: ROS_DISTRO=rolling gives Rolling's
`lifecycle_msgs/msg/TransitionEvent` (a `builtin_interfaces/Time stamp` where Jazzy and
Kilted have `uint64 timestamp`), with its own RIHS01 hash; every other distro keeps Jazzy's."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from rosbags.typesys import Stores, get_types_from_msg, get_typestore

REFERENCE = Path(__file__).resolve().parents[3] / 'shared' / 'reference' / 'rihs01_jazzy.json'
NAME = 'lifecycle_msgs/msg/TransitionEvent'
ROLLING_TEXT = (
    'builtin_interfaces/Time stamp\nlifecycle_msgs/Transition transition\n'
    'lifecycle_msgs/State start_state\nlifecycle_msgs/State goal_state\n'
)


def _rosbags_rolling_hash() -> str:
    """rosbags' own RIHS01 of Rolling's definition (written here from the Rolling change, not
    read from ros2lite), over Jazzy's State and Transition."""
    jazzy = get_typestore(Stores.ROS2_JAZZY)
    store = get_typestore(Stores.EMPTY)
    store.register(
        {
            k: v
            for k, v in jazzy.fielddefs.items()
            if k.startswith(
                ('lifecycle_msgs/msg/State', 'lifecycle_msgs/msg/Transition', 'builtin')
            )
            and k != NAME
        }
    )
    store.register(get_types_from_msg(ROLLING_TEXT, NAME))
    return str(store.hash_rihs01(NAME))


def _in(distro: str, code: list[str]) -> str:
    env = {**os.environ, 'ROS_DISTRO': distro}
    run = subprocess.run(
        [sys.executable, *code], capture_output=True, text=True, env=env, timeout=60
    )
    assert run.returncode == 0, run.stderr
    return run.stdout


HASH = ['-c', f'from ros2lite.interfaces.hashing import type_hash; print(type_hash({NAME!r}))']


def test_rolling_has_its_own_transition_event() -> None:
    assert _in('rolling', HASH).strip() == _rosbags_rolling_hash()
    shown = _in('rolling', ['-m', 'ros2lite', 'interface', 'show', NAME])
    assert 'builtin_interfaces/Time stamp' in shown and 'timestamp' not in shown


@pytest.mark.parametrize('distro', ['jazzy', 'kilted', ''])
def test_other_distros_keep_jazzys(distro: str) -> None:
    if REFERENCE.is_file():
        assert _in(distro, HASH).strip() == json.loads(REFERENCE.read_text())[NAME]
    assert _rosbags_rolling_hash() != _in(distro, HASH).strip()
