"""`.rviz` files read into the viewer's displays: rviz2's own layout, groups, old-style
topics, the view, and hostile input refused in one line."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from ros2lite.bundled.rviz2.config import ConfigError, DisplaySpec, load, parse


def test_displays_fixed_frame_and_orbit_view() -> None:
    config = parse(
        {
            'Visualization Manager': {
                'Displays': [
                    {'Class': 'rviz_default_plugins/Grid', 'Name': 'Grid'},
                    {
                        'Class': 'rviz_common/Group',
                        'Displays': [
                            {
                                'Class': 'rviz_default_plugins/LaserScan',
                                'Topic': {'Value': '/scan'},
                            },
                            {'Class': 'rviz_default_plugins/Map', 'Topic': 'map', 'Enabled': False},
                        ],
                    },
                    {'Class': 'rviz_default_plugins/RobotModel'},
                    {'Class': 'nav2_rviz_plugins/ParticleCloud', 'Topic': {'Value': '/pc'}},
                ],
                'Global Options': {'Fixed Frame': 'odom'},
                'Views': {
                    'Current': {
                        'Class': 'rviz_default_plugins/Orbit',
                        'Distance': 2.0,
                        'Pitch': 0.0,
                        'Yaw': 0.0,
                        'Focal Point': {'X': 1, 'Y': 0},
                    }
                },
            }
        }
    )
    assert config.fixed_frame == 'odom'
    assert [(d.kind, d.topic, d.enabled) for d in config.displays] == [
        ('Grid', '', True),
        ('LaserScan', '/scan', True),
        ('Map', '/map', False),
        ('RobotModel', '/robot_description', True),
    ]
    assert config.skipped == ('nav2_rviz_plugins/ParticleCloud',)
    assert config.view is not None
    assert all(
        math.isclose(a, b, abs_tol=1e-9)
        for a, b in zip(config.view.position, (3, 0, 0), strict=True)
    )
    assert isinstance(config.displays[0], DisplaySpec)


@pytest.mark.parametrize(
    'text',
    [
        '- a list',
        'Visualization Manager: 3',
        'Visualization Manager: {Displays: [{Class: x/LaserScan}]}',
        'a: &a [*a',
        '!!python/object:os.system {}',
    ],
)
def test_bad_files_are_one_line(tmp_path: Path, text: str) -> None:
    path = tmp_path / 'bad.rviz'
    path.write_text(text)
    with pytest.raises(ConfigError) as e:
        load(str(path))
    assert '\n' not in str(e.value) and str(path) in str(e.value)


def test_missing_file(tmp_path: Path) -> None:
    with pytest.raises(ConfigError, match='cannot read'):
        load(str(tmp_path / 'none.rviz'))


def test_the_address_printed_is_one_to_open() -> None:
    import socket

    from ros2lite.bundled.rviz2.viewer import page_url

    assert page_url('127.0.0.1', 8080) == 'http://127.0.0.1:8080'
    assert page_url('0.0.0.0', 8081) == f'http://{socket.gethostname()}:8081'
    assert page_url('::', 8081) == f'http://{socket.gethostname()}:8081'
    assert page_url('::1', 9000) == 'http://[::1]:9000'
