"""2D simulator benchmarks (issue 35's bars), on a real router with the simulator as its own
process (`ros2lite run turtlebot3_gazebo gazebo_2d`) and a subscriber to /clock and /scan in
this one, so the laser is drawn as it is when a node listens.

`sim_rtf10_wall`: wall seconds for 60 s of sim time at a real-time factor of 10 (burger in
turtlebot3_world, /scan subscribed). Bar: <= 8 s; the ratio is against the ideal 6 s.
`sim_cpu_1x`: the simulator process' CPU (user + system, of one core) at 1x over 10 s, its
360-beam laser made to run at 10 Hz. Bar: < 15 %; the ratio is against that 15 %.
"""

from __future__ import annotations

import os
import random
import subprocess
import sys
import tempfile
import time

from common import cli_env, environment, free_port, report, router_process


def _cpu_seconds(pid: int) -> float:
    with open(f'/proc/{pid}/stat') as f:
        fields = f.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


def _with_sim(params: list[str], measure) -> float:
    endpoint = f'tcp/127.0.0.1:{free_port()}'
    domain = str(random.randint(100, 232))
    with tempfile.TemporaryDirectory() as runtime:
        env = cli_env(endpoint, domain, runtime)
        env['ROS2LITE_NO_DAEMON'] = '1'
        with router_process(endpoint), environment(env):
            args = [a for p in params for a in ('-p', p)]
            sim = subprocess.Popen(
                # the executable's module itself: its pid is the simulator's (no `run` parent)
                [
                    sys.executable,
                    '-m',
                    'ros2lite.bundled.turtlebot3_gazebo.gazebo_2d',
                    '--ros-args',
                    *args,
                ],
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                env=env,
            )
            try:
                return measure(sim)
            finally:
                sim.terminate()
                sim.wait(10)


def _listener():
    import ros2lite
    from ros2lite.executors import SingleThreadedExecutor
    from ros2lite.msgs.rosgraph_msgs.msg import Clock
    from ros2lite.msgs.sensor_msgs.msg import LaserScan
    from ros2lite.node import Node
    from ros2lite.qos import qos_profile_sensor_data

    ros2lite.init()
    node = Node('bench_sim_listener')
    state = {'clock': -1.0, 'scans': 0}

    def on_clock(msg: Clock) -> None:
        state['clock'] = msg.clock.sec + msg.clock.nanosec * 1e-9

    def on_scan(msg: LaserScan) -> None:
        state['scans'] += 1

    node.create_subscription(Clock, '/clock', on_clock, 10)
    node.create_subscription(LaserScan, '/scan', on_scan, qos_profile_sensor_data)
    executor = SingleThreadedExecutor()
    executor.add_node(node)
    return executor, node, state


def _spin_until(executor, predicate, timeout: float) -> None:
    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            raise RuntimeError('the simulator did not answer in time')
        executor.spin_once(timeout_sec=0.01)


def bench_rtf10() -> None:
    def measure(sim) -> float:
        import ros2lite

        executor, node, state = _listener()
        try:
            _spin_until(executor, lambda: state['scans'] > 0 and state['clock'] >= 0, 60)
            start_sim, start = state['clock'], time.monotonic()
            _spin_until(executor, lambda: state['clock'] >= start_sim + 60.0, 60)
            return time.monotonic() - start
        finally:
            executor.shutdown()
            node.destroy_node()
            ros2lite.shutdown()

    seconds = _with_sim(['real_time_factor:=10.0'], measure)
    report('sim_rtf10_wall', seconds, 's', seconds / 6.0)


def bench_cpu() -> None:
    def measure(sim) -> float:
        import ros2lite

        executor, node, state = _listener()
        try:
            _spin_until(executor, lambda: state['scans'] > 2, 60)
            cpu0, t0 = _cpu_seconds(sim.pid), time.monotonic()
            scans0 = state['scans']
            _spin_until(executor, lambda: time.monotonic() - t0 >= 10.0, 30)
            share = (_cpu_seconds(sim.pid) - cpu0) / (time.monotonic() - t0)
            rate = (state['scans'] - scans0) / (time.monotonic() - t0)
            print(f'# sim_cpu_1x: {rate:.1f} scans/s received', flush=True)
            return share
        finally:
            executor.shutdown()
            node.destroy_node()
            ros2lite.shutdown()

    share = _with_sim(['real_time_factor:=1.0', 'scan_rate:=10.0'], measure)
    report('sim_cpu_1x', share * 100, '%', share / 0.15)


BENCHES = {'sim_rtf10_wall': bench_rtf10, 'sim_cpu_1x': bench_cpu}
