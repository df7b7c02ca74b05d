"""The `/turtlesim` node as a ROS user meets it: every topic, service, parameter and the
action, through the CLI verbs of the turtlesim lesson, against a real node process."""

from __future__ import annotations

import re
import time
from collections.abc import Callable
from typing import Any

import yaml

from tests.bundled.turtlesim.conftest import log_line, wait_for_log
from tests.cli.conftest import Result


def wait_for(run: Callable[..., Result], args: tuple[str, ...], text: str, present: bool) -> str:
    deadline = time.monotonic() + 15
    while True:
        out = run(*args).out
        if (text in out.split('\n')) == present:
            return out
        assert time.monotonic() < deadline, out
        time.sleep(0.1)


def pose(run: Callable[..., Result], turtle: str = 'turtle1') -> dict[str, float]:
    result = run('topic', 'echo', '--once', f'/{turtle}/pose')
    assert result.code == 0, result.err
    return dict(yaml.safe_load(result.out.split('---')[0]))


def settle(
    run: Callable[..., Result],
    turtle: str = 'turtle1',
    *,
    moved_from: dict[str, float] | None = None,
) -> dict[str, float]:
    """The pose once the turtle stands still (its last command over). With `moved_from`, the
    pose it stood in before a command was sent: a command takes a moment to reach the
    simulator (longer under load), and until it has, the turtle still stands there."""
    deadline = time.monotonic() + 10
    while True:
        p = pose(run, turtle)
        moved = moved_from is None or any(p[k] != moved_from[k] for k in ('x', 'y', 'theta'))
        if moved and p['linear_velocity'] == 0.0 and p['angular_velocity'] == 0.0:
            return p
        assert time.monotonic() < deadline, p
        time.sleep(0.1)


def test_topics_services_and_node_info(run: Callable[..., Result], turtlesim: Any) -> None:
    proc, lines = turtlesim
    assert re.fullmatch(
        log_line('turtlesim', r'Starting turtlesim with node name /turtlesim'), lines[0]
    ), lines
    assert lines[1].endswith(
        '[turtlesim]: Spawning turtle [turtle1] at x=[5.544445], y=[5.544445], theta=[0.000000]'
    ), lines
    topics = run('topic', 'list', '-t').out.split('\n')
    for line in (
        '/turtle1/cmd_vel [geometry_msgs/msg/Twist]',
        '/turtle1/color_sensor [turtlesim/msg/Color]',
        '/turtle1/pose [turtlesim/msg/Pose]',
    ):
        assert line in topics
    services = run('service', 'list').out.split('\n')
    for name in ('/clear', '/kill', '/reset', '/spawn', '/turtle1/set_pen'):
        assert name in services
    assert '/turtle1/teleport_absolute' in services and '/turtle1/teleport_relative' in services
    info = run('node', 'info', '/turtlesim').out
    assert '  Subscribers:\n    /parameter_events: rcl_interfaces/msg/ParameterEvent\n' in info
    assert '    /turtle1/cmd_vel: geometry_msgs/msg/Twist\n' in info
    assert '  Action Servers:\n    /turtle1/rotate_absolute: turtlesim/action/RotateAbsolute\n' in (
        info
    )
    p = pose(run)
    assert p['x'] == p['y'] == 5.544444561004639 and p['theta'] == 0.0
    assert run('topic', 'echo', '--once', '/turtle1/color_sensor').out.startswith('r: 255\n')
    assert 'Publisher count: 1' in run('topic', 'info', '/turtle1/pose').out

    # drive: a Twist lasts one second, then the turtle stops
    still = pose(run)
    run(
        'topic',
        'pub',
        '--once',
        '-w',
        '1',
        '/turtle1/cmd_vel',
        'geometry_msgs/msg/Twist',
        '{linear: {x: 2.0}}',
    )
    p = settle(run, moved_from=still)
    assert 7.4 < p['x'] < 7.6 and p['y'] == 5.544444561004639  # 62 or 63 steps at 2 m/s

    # spawn: a second turtle with its own interface; kill: it goes
    out = run('service', 'call', '/spawn', 'turtlesim/srv/Spawn', '{x: 2, y: 2, theta: 0.2}').out
    assert "turtlesim.srv.Spawn_Response(name='turtle2')" in out
    wait_for(run, ('topic', 'list'), '/turtle2/pose', True)
    assert pose(run, 'turtle2')['theta'] == 0.20000000298023224
    out = run('service', 'call', '/spawn', 'turtlesim/srv/Spawn', '{name: turtle2}').out
    assert "Spawn_Response(name='')" in out  # taken
    run('service', 'call', '/kill', 'turtlesim/srv/Kill', '{name: turtle2}')
    wait_for(run, ('topic', 'list'), '/turtle2/pose', False)
    assert '/turtle2/set_pen' not in run('service', 'list').out.split('\n')
    run('service', 'call', '/kill', 'turtlesim/srv/Kill', '{name: nobody}')

    # teleport and pen
    run(
        'service',
        'call',
        '/turtle1/set_pen',
        'turtlesim/srv/SetPen',
        '{r: 255, g: 0, b: 0, width: 5}',
    )
    run(
        'service',
        'call',
        '/turtle1/teleport_absolute',
        'turtlesim/srv/TeleportAbsolute',
        '{x: 1.0, y: 1.0, theta: 1.0}',
    )
    p = pose(run)
    assert (p['x'], p['y'], p['theta']) == (1.0, 1.0, 1.0)
    # the teleport drew a red line, which the turtle now stands on
    assert run('topic', 'echo', '--once', '/turtle1/color_sensor').out.startswith(
        'r: 255\ng: 0\nb: 0\n'
    )
    run(
        'service',
        'call',
        '/turtle1/teleport_relative',
        'turtlesim/srv/TeleportRelative',
        '{linear: 1.0, angular: 0.0}',
    )
    assert abs(pose(run)['x'] - (1.0 + 0.5403023)) < 1e-5
    run('service', 'call', '/clear', 'std_srvs/srv/Empty')
    assert run('topic', 'echo', '--once', '/turtle1/color_sensor').out.startswith('r: 255\ng: 255')

    # reset: one turtle1 at the centre again, names count from turtle1 again
    run('service', 'call', '/spawn', 'turtlesim/srv/Spawn', '{x: 3, y: 3}')
    run('service', 'call', '/reset', 'std_srvs/srv/Empty')
    wait_for(run, ('topic', 'list'), '/turtle2/pose', False)
    p = pose(run)
    assert p['x'] == 5.544444561004639 and p['theta'] == 0.0

    # the walls: driving into one clamps and warns with turtlesim's line
    still = pose(run)
    run(
        'topic',
        'pub',
        '--once',
        '-w',
        '1',
        '/turtle1/cmd_vel',
        'geometry_msgs/msg/Twist',
        '{linear: {x: 9.0}}',
    )
    p = settle(run, moved_from=still)
    assert p['x'] == 11.088889122009277
    wall = wait_for_log(proc, lines, r'Oh no! I hit the wall!')
    assert re.search(
        r'\[WARN\] \[\d+\.\d+\] \[turtlesim\]: Oh no! I hit the wall! '
        r'\(Clamping from \[x=11\.\d{6}, y=5\.544444\]\)$',
        wall.rstrip(),
    ), wall
    for text in ('Clearing turtlesim.', 'Resetting turtlesim.'):
        assert any(line.endswith(f'[turtlesim]: {text}') for line in lines), lines
    wait_for_log(proc, lines, r'Tried to kill turtle \[nobody\], which does not exist')
    assert any(
        '[ERROR]' in line and 'A turtle named [turtle2] already exists' in line for line in lines
    )


def test_parameters(run: Callable[..., Result], turtlesim: Any, tmp_path: Any) -> None:
    names = run('param', 'list', '/turtlesim').out.split('\n')
    for name in ('background_b', 'background_g', 'background_r', 'holonomic'):
        assert f'  {name}' in names
    assert run('param', 'get', '/turtlesim', 'background_r').out == 'Integer value is: 69\n'
    assert run('param', 'get', '/turtlesim', 'background_g').out == 'Integer value is: 86\n'
    assert run('param', 'get', '/turtlesim', 'background_b').out == 'Integer value is: 255\n'
    described = run('param', 'describe', '/turtlesim', 'background_r').out
    assert 'Description: Red channel of the background color' in described
    assert 'Min value: 0' in described and 'Max value: 255' in described
    ok = run('param', 'set', '/turtlesim', 'background_r', '150')
    assert (ok.code, ok.out) == (0, 'Set parameter successful\n')
    assert run('param', 'get', '/turtlesim', 'background_r').out == 'Integer value is: 150\n'
    refused = run('param', 'set', '/turtlesim', 'background_r', '300')
    assert refused.err == (
        'Setting parameter failed: Parameter background_r out of range. '
        'Min: 0, Max: 255, value: 300\n'
    )
    dump = yaml.safe_load(run('param', 'dump', '/turtlesim').out)
    assert dump['/turtlesim']['ros__parameters']['background_r'] == 150
    path = tmp_path / 'turtlesim.yaml'
    dump['/turtlesim']['ros__parameters']['background_g'] = 10
    path.write_text(yaml.safe_dump(dump))
    loaded = run('param', 'load', '/turtlesim', str(path))
    assert 'Set parameter background_g successful' in loaded.out
    assert run('param', 'get', '/turtlesim', 'background_g').out == 'Integer value is: 10\n'

    # holonomic, applied live: linear.y now moves the turtle sideways
    run('param', 'set', '/turtlesim', 'holonomic', 'true')
    still = pose(run)
    run(
        'topic',
        'pub',
        '--once',
        '-w',
        '1',
        '/turtle1/cmd_vel',
        'geometry_msgs/msg/Twist',
        '{linear: {y: 1.0}}',
    )
    p = settle(run, moved_from=still)
    assert p['x'] == 5.544444561004639 and 6.5 < p['y'] < 6.6


def test_parameters_from_the_command_line(run: Callable[..., Result], processes: Any) -> None:
    from tests.bundled.turtlesim.conftest import start_turtlesim

    start_turtlesim(
        processes,
        '--display',
        'none',
        '--ros-args',
        '-p',
        'background_r:=12',
        '-r',
        '__ns:=/sim',
        '-r',
        'turtle1/pose:=/p1',
    )
    assert run('param', 'get', '/sim/turtlesim', 'background_r').out == 'Integer value is: 12\n'
    topics = run('topic', 'list').out.split('\n')
    assert '/p1' in topics and '/sim/turtle1/cmd_vel' in topics


def test_rotate_absolute_action(run: Callable[..., Result], turtlesim: Any) -> None:
    proc, lines = turtlesim
    actions = run('action', 'list', '-t').out
    assert '/turtle1/rotate_absolute [turtlesim/action/RotateAbsolute]' in actions
    info = run('action', 'info', '/turtle1/rotate_absolute').out
    assert 'Action servers: 1\n    /turtlesim\n' in info
    result = run(
        'action',
        'send_goal',
        '/turtle1/rotate_absolute',
        'turtlesim/action/RotateAbsolute',
        '{theta: 1.57}',
        '--feedback',
    )
    assert result.code == 0, result.err
    out = result.out
    assert 'Sending goal:\n     theta: 1.57\n' in out
    remaining = [float(v) for v in re.findall(r'Feedback:\n    remaining: (\S+)\n', out)]
    assert len(remaining) > 50 and remaining[0] > 1.5 and remaining[-1] < 0.05
    delta = float(re.search(r'Result:\n    delta: (\S+)\n', out)[1])  # type: ignore[index]
    assert -1.57 < delta < -1.53
    assert out.endswith('Goal finished with status: SUCCEEDED\n')
    wait_for_log(proc, lines, r'\[turtlesim\]: Rotation goal completed successfully$')
    assert abs(pose(run)['theta'] - 1.57) < 0.02

    # a Twist during a goal aborts it (the real node's rule), with its warning
    import threading

    holder: list[Result] = []
    goal = threading.Thread(
        target=lambda: holder.append(
            run(
                'action',
                'send_goal',
                '/turtle1/rotate_absolute',
                'turtlesim/action/RotateAbsolute',
                '{theta: -1.57}',
            )
        )
    )
    goal.start()
    time.sleep(1.0)
    run('topic', 'pub', '--once', '-w', '1', '/turtle1/cmd_vel', 'geometry_msgs/msg/Twist', '{}')
    goal.join(30)
    assert holder and holder[0].out.endswith('Goal finished with status: ABORTED\n'), holder
    wait_for_log(proc, lines, r'Velocity command received during rotation goal. Aborting goal$')


def test_nan_and_infinity_are_refused_and_the_node_lives(
    run: Callable[..., Result], turtlesim: Any
) -> None:
    """R-W13: a NaN in cmd_vel (or /spawn, a teleport) ended the node ('cannot convert float
    NaN to integer')."""
    proc, lines = turtlesim
    before = pose(run)
    sent = [
        ('topic', 'pub', '-t', '1', '-w', '1', '/turtle1/cmd_vel', 'geometry_msgs/msg/Twist',
         '{linear: {x: .nan}}'),
        ('service', 'call', '/spawn', 'turtlesim/srv/Spawn',
         '{x: .nan, y: .inf, theta: 0.2, name: n}'),
        ('service', 'call', '/turtle1/teleport_absolute', 'turtlesim/srv/TeleportAbsolute',
         '{x: .nan, y: 1.0, theta: .inf}'),
        ('service', 'call', '/turtle1/teleport_relative', 'turtlesim/srv/TeleportRelative',
         '{linear: .inf, angular: .nan}'),
        ('action', 'send_goal', '/turtle1/rotate_absolute', 'turtlesim/action/RotateAbsolute',
         '{theta: -.inf}'),
        # R5: finite, but past what the float32 Pose holds (it ended the node in packing)
        ('topic', 'pub', '-t', '1', '-w', '1', '/turtle1/cmd_vel', 'geometry_msgs/msg/Twist',
         '{linear: {x: 1.0e+308}}'),
    ]  # fmt: skip
    for args in sent:
        assert run(*args).code == 0, args
    for what, values in [
        ('velocity command', 'linear_x=nan'),
        ('spawn request', 'x=nan, y=inf'),
        ('teleport', 'x=nan, theta=inf'),
        ('teleport', 'linear=inf, angular=nan'),
        ('rotation goal', 'theta=-inf'),
        ('velocity command', 'linear_x=1e+308'),
    ]:
        line = f'Ignoring a {what} with a value that is not a finite float32 ({values})'
        wait_for_log(proc, lines, re.escape(line))
    assert proc.poll() is None
    assert '/n/pose' not in run('topic', 'list').out.split('\n')
    after = pose(run)
    assert all(after[k] == before[k] for k in ('x', 'y', 'theta')), (before, after)
