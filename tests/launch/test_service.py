"""The launch service with plain processes: output, events, timers, conditions, scopes,
shutdown and escalation, errors — launch's behaviour, without ROS in the way."""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from ros2lite.launch.actions import DeclareLaunchArgument, OpaqueFunction, SetLaunchConfiguration
from ros2lite.launch.conditions import IfCondition, UnlessCondition
from ros2lite.launch.event_handlers import OnProcessExit, OnProcessIO, OnProcessStart
from ros2lite.launch.events import Shutdown
from ros2lite.launch.flow import (
    EmitEvent,
    GroupAction,
    IncludeLaunchDescription,
    LogInfo,
    RegisterEventHandler,
    TimerAction,
)
from ros2lite.launch.sources import PythonLaunchDescriptionSource
from ros2lite.launch.substitutions import LaunchConfiguration
from tests.launch.helpers import run_launch, sh

PID = re.compile(r'\d+')


def _plain(lines: list[str]) -> list[str]:
    return [PID.sub('N', line) for line in lines]


def test_processes_output_and_exit(tmp_path: Path) -> None:
    code, lines, _service = run_launch(
        [
            sh('echo to-out; echo to-err >&2'),
            sh('echo hidden; echo shown >&2; exit 2', name='quiet', output='log'),
        ],
        tmp_path,
    )
    assert code == 0
    log_dir = tmp_path / 'log'
    assert lines[:2] == [
        f'[INFO] [launch]: All log files can be found below {log_dir}',
        '[INFO] [launch]: Default logging verbosity is set to INFO',
    ]
    plain = _plain(lines)
    assert '[INFO] [sh-N]: process started with pid [N]' in plain
    assert {'[sh-1] to-out', '[sh-1] to-err', '[quiet-2] shown'} <= set(lines)
    assert '[quiet-2] hidden' not in lines  # output='log': stdout to the log file only
    assert '[INFO] [sh-N]: process has finished cleanly [pid N]' in plain
    assert (
        "[ERROR] [quiet-N]: process has died [pid N, exit code N, cmd 'sh -c echo hidden; "
        "echo shown >&N; exit N']." in plain
    )
    log = (log_dir / 'launch.log').read_text().splitlines()
    assert re.match(r'\d+\.\d{7} \[INFO\] \[launch\]: All log files', log[0])
    assert any(line.endswith(' [quiet-2] hidden') for line in log)


def test_events_timers_conditions_and_scopes(tmp_path: Path) -> None:
    first = sh('echo first')
    seen: list[str] = []

    def opaque(context: Any, suffix: str) -> list[Any]:
        return [LogInfo(msg=['opaque ', LaunchConfiguration('who'), suffix])]

    code, lines, _ = run_launch(
        [
            SetLaunchConfiguration('who', 'outer'),
            RegisterEventHandler(
                OnProcessExit(
                    target_action=first, on_exit=[LogInfo(msg='first exited'), sh('echo second')]
                )
            ),
            RegisterEventHandler(
                OnProcessStart(
                    target_action=first,
                    on_start=lambda event, ctx: LogInfo(msg=f'started {event.process_name}'),
                )
            ),
            RegisterEventHandler(
                OnProcessIO(on_stdout=lambda event: seen.append(event.text.decode()))
            ),
            first,
            TimerAction(period=0.3, actions=[LogInfo(msg='timer fired')]),
            LogInfo(msg='never', condition=IfCondition('false')),
            LogInfo(msg='unless', condition=UnlessCondition('0')),
            GroupAction(
                [SetLaunchConfiguration('who', 'inner'), LogInfo(msg=LaunchConfiguration('who'))]
            ),
            OpaqueFunction(function=opaque, args=['!']),
        ],
        tmp_path,
    )
    assert code == 0
    logs = [line.split(': ', 1)[1] for line in lines if line.startswith('[INFO] [launch.user]')]
    assert 'never' not in logs
    assert logs[:3] == ['unless', 'inner', 'opaque outer!']  # the group's value stayed inside
    assert {'first exited', 'timer fired'} <= set(logs)
    assert '[INFO] [launch.user]: started sh-1' in lines
    assert lines.index('[sh-1] first') < lines.index('[sh-2] second')
    assert seen == ['first\n', 'second\n']


def test_a_timer_keeps_the_scope_it_was_set_in(tmp_path: Path) -> None:
    """A timer inside a group fires after the group has ended: its actions still see the
    group's configurations (as launch does since ros2/launch#836), and what they set stays
    theirs."""
    code, lines, _ = run_launch(
        [
            SetLaunchConfiguration('who', 'outer'),
            GroupAction(
                [
                    SetLaunchConfiguration('who', 'inner'),
                    TimerAction(
                        period=0.1,
                        actions=[
                            LogInfo(msg=['timer sees ', LaunchConfiguration('who')]),
                            SetLaunchConfiguration('who', 'timer'),
                        ],
                    ),
                ]
            ),
            TimerAction(period=0.3, actions=[LogInfo(msg=['later ', LaunchConfiguration('who')])]),
        ],
        tmp_path,
    )
    assert code == 0
    logs = [line.split(': ', 1)[1] for line in lines if line.startswith('[INFO] [launch.user]')]
    assert logs == ['timer sees inner', 'later outer']


def test_a_shutdown_stops_what_runs(tmp_path: Path) -> None:
    done = sh('exit 0')
    code, lines, _ = run_launch(
        [
            sh(
                "trap 'echo got INT; exit 0' INT; echo ready; while :; do sleep 0.05; done",
                name='sleeper',
            ),
            RegisterEventHandler(
                OnProcessExit(
                    target_action=done, on_exit=[EmitEvent(event=Shutdown(reason='done'))]
                )
            ),
            done,
        ],
        tmp_path,
    )
    assert code == 0
    assert "[INFO] [sleeper-1]: sending signal 'SIGINT' to process[sleeper-1]" in lines
    assert '[sleeper-1] got INT' in lines
    assert '[INFO] [sleeper-N]: process has finished cleanly [pid N]' in _plain(lines)


def test_escalation_to_sigterm_and_sigkill(tmp_path: Path) -> None:
    stubborn = sh(
        "trap '' INT TERM; echo ready; while :; do sleep 0.05; done",
        name='stubborn',
        sigterm_timeout='0.3',
        sigkill_timeout='0.3',
    )
    code, lines, _ = run_launch(
        [
            # registered first: a handler sees only what happens after it is registered
            RegisterEventHandler(
                OnProcessIO(
                    target_action=stubborn,
                    on_stdout=lambda event: EmitEvent(event=Shutdown(reason='test')),
                )
            ),
            stubborn,
        ],
        tmp_path,
    )
    assert code == 0
    plain = _plain(lines)
    assert (
        "[ERROR] [stubborn-1]: process[stubborn-1] failed to terminate '0.3' seconds after "
        "receiving 'SIGINT', escalating to 'SIGTERM'" in lines
    )
    assert (
        "[ERROR] [stubborn-1]: process[stubborn-1] failed to terminate '0.6' seconds after "
        "receiving 'SIGTERM', escalating to 'SIGKILL'" in lines
    )
    assert any(
        line.startswith('[ERROR] [stubborn-N]: process has died [pid N, exit code -N')
        for line in plain
    )


def test_an_error_stops_the_launch(tmp_path: Path) -> None:
    code, lines, _ = run_launch(
        [sh('sleep 30', name='early'), DeclareLaunchArgument('needed', description='a value')],
        tmp_path,
    )
    assert code == 1
    assert (
        '[ERROR] [launch]: Caught exception in launch (see debug for traceback): Required '
        'launch argument "needed" (description: "a value") was not provided' in lines
    )
    assert "[INFO] [early-1]: sending signal 'SIGINT' to process[early-1]" in lines


def test_including_a_python_launch_file(tmp_path: Path) -> None:
    included = tmp_path / 'child.launch.py'
    included.write_text(
        'from launch import LaunchDescription\n'
        'from launch.actions import DeclareLaunchArgument, LogInfo\n'
        'from launch.substitutions import LaunchConfiguration, ThisLaunchFileDir\n\n'
        'def generate_launch_description():\n'
        '    return LaunchDescription([\n'
        "        DeclareLaunchArgument('greeting'),\n"
        "        DeclareLaunchArgument('name', default_value='world'),\n"
        "        LogInfo(msg=[LaunchConfiguration('greeting'), ' ', LaunchConfiguration('name'),\n"
        "                     ' from ', ThisLaunchFileDir()]),\n"
        '    ])\n'
    )
    source = PythonLaunchDescriptionSource(str(included))
    code, lines, _ = run_launch(
        [IncludeLaunchDescription(source, launch_arguments={'greeting': 'hello'}.items())],
        tmp_path,
    )
    assert code == 0
    assert f'[INFO] [launch.user]: hello world from {tmp_path}' in lines
    code, lines, _ = run_launch(
        [IncludeLaunchDescription(PythonLaunchDescriptionSource(str(included)))], tmp_path
    )
    assert code == 1
    assert any("missing required argument 'greeting'" in line for line in lines)


def test_respawn(tmp_path: Path) -> None:
    code, lines, _ = run_launch(
        [
            sh(
                'echo run; exit 1',
                name='flaky',
                respawn=True,
                respawn_delay=0.05,
                respawn_max_retries=2,
            )
        ],
        tmp_path,
    )
    assert code == 0
    assert lines.count('[flaky-1] run') == 3
