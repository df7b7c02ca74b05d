"""`topic plot` of a 1 kHz topic: does it keep up, and at what CPU cost?

A publisher process sends std_msgs/Float64 with data = 1, 2, 3 … at 1 kHz for 6 s; the real
CLI `topic plot /bench_plot/data` draws it live on a pseudo-terminal (so the braille frames
are drawn as on a user's screen, 10 a second). Measured:

* plot_cpu_1khz: the plot process' CPU time (user + system, /proc) over the steady middle 3 s
  of the run, as % of one core; ratio = that / the 20 % target (below 1 meets it).
* plot_sent_rate: what the publisher really sent (count / its run time); ratio = / 1000.
* plot_rate_1khz: the rate the plot's own readout shows in the middle of the run; ratio =
  rate / the sent rate (a plot that falls behind drops samples: sensor-data QoS).
* plot_cpu_vs_topic_hz: `topic hz` of the same topic (nothing decoded or drawn: the cost of
  receiving 1 kHz at all), as % of a core; ratio = plot's CPU / hz's.
* plot_lag_after_end: after the last message, how many messages behind the readout's value
  is once the picture settles (0: nothing queued, nothing lost at the end); ratio = lag / 1.
"""

from __future__ import annotations

import os
import re
import select
import subprocess
import sys
import time

from bench_topic import private_router
from common import Terminal, report

RATE = 1000.0
SECONDS = 6.0
TARGET_CPU = 0.20
EXTRA = os.environ.get('PLOT_EXTRA', '').split()

PUBLISHER = r'''
import sys, time
from ros2lite.context import Context
from ros2lite.node import Node
from ros2lite.interfaces import get_interface
from ros2lite.qos import qos_profile_sensor_data
topic, hz, seconds = sys.argv[1], float(sys.argv[2]), float(sys.argv[3])
ctx = Context(); ctx.init([])
node = Node('bench_plot_publisher', context=ctx, enable_rosout=False)
Float64 = get_interface('std_msgs/msg/Float64')
pub = node.create_publisher(Float64, topic, qos_profile_sensor_data)
while pub.get_subscription_count() < 1:
    time.sleep(0.02)
time.sleep(0.5)
print('start', flush=True)
count = int(hz * seconds)
start = time.monotonic()
for i in range(1, count + 1):
    ahead = start + i / hz - time.monotonic()
    if ahead > 0:
        time.sleep(ahead)
    pub.publish(Float64(data=float(i)))
print('done', count, count / (time.monotonic() - start), flush=True)
time.sleep(1.0)
ctx.shutdown()
'''
LEGEND = re.compile(r'/bench_plot/data = ([\d.e+]+)\s+([\d.]+) Hz')
ANSI = re.compile(r'\x1b\[[0-9;?]*[A-Za-z]')


def cpu_seconds(pid: int) -> float:
    with open(f'/proc/{pid}/stat') as f:
        fields = f.read().rsplit(')', 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf('SC_CLK_TCK')


def trial(args: list[str]) -> tuple[float, list[str], int, float]:
    """Run `ros2lite ARGS` on a 120x30 pseudo-terminal while the publisher sends; returns
    (its CPU share over the steady middle 3 s, the screen output, messages sent, sent rate)."""
    with private_router() as env:
        env = {**env, 'TERM': 'xterm-256color', 'ROS2LITE_NO_DAEMON': '1'}
        env.pop('NO_COLOR', None)
        term = Terminal([sys.executable, '-m', 'ros2lite', *args], env, 30, 120)
        tool = term.proc
        publisher = subprocess.Popen(
            [sys.executable, '-c', PUBLISHER, '/bench_plot', str(RATE), str(SECONDS)],
            env=env,
            stdout=subprocess.PIPE,
            text=True,
        )
        assert publisher.stdout is not None
        ready, _, _ = select.select([publisher.stdout], [], [], 20)
        if not ready or publisher.stdout.readline().strip() != 'start':
            publisher.kill()
            tool.kill()
            raise RuntimeError(f'no subscription came: {term.output()[-800:]!r}')
        time.sleep(1.5)
        cpu0, t0 = cpu_seconds(tool.pid), time.monotonic()
        time.sleep(3.0)
        cpu1, t1 = cpu_seconds(tool.pid), time.monotonic()
        middle = len(term.chunks)
        done = publisher.stdout.readline().split()
        time.sleep(0.5)  # a few frames after the last message
        publisher.wait(10)
        term.close()
    screen = [chunk.decode('utf-8', 'replace') for chunk in term.chunks]
    screen.insert(middle, '\0')  # where the middle of the run was
    return (cpu1 - cpu0) / (t1 - t0), screen, int(done[1]), float(done[2])


def bench_plot_1khz() -> None:
    fraction, screen, count, sent_rate = trial(['topic', 'plot', '/bench_plot/data', *EXTRA])
    text = ''.join(screen)
    middle, end = text.split('\0')
    rates = [float(m[1]) for m in LEGEND.findall(ANSI.sub('', middle[-20000:]))]
    last = LEGEND.findall(ANSI.sub('', end))
    if not last or not rates:
        raise RuntimeError(f'no readout on the plot screen: {text[-500:]!r}')
    hz_fraction = trial(['topic', 'hz', '/bench_plot'])[0]
    report('plot_cpu_1khz', fraction * 100, '%', fraction / TARGET_CPU)
    report('plot_cpu_vs_topic_hz', hz_fraction * 100, '%', fraction / hz_fraction)
    report('plot_sent_rate', sent_rate, 'Hz', sent_rate / RATE)
    report('plot_rate_1khz', rates[-1], 'Hz', rates[-1] / sent_rate)
    lag = count - float(last[-1][0])
    report('plot_lag_after_end', lag, 'messages', lag / 1)


BENCHES = {'plot_1khz': bench_plot_1khz}
