"""`tf2_monitor [FRAME_A FRAME_B]`: how late transforms arrive, per frame and overall, and
(given two frames) the chain between them and its net delay; a report every ~10 seconds, in
tf2_ros's tf2_monitor layout."""

from __future__ import annotations

import sys
from collections import deque
from typing import TYPE_CHECKING

from ros2lite.bundled.display import own_arguments
from ros2lite.bundled.runner import run_node
from ros2lite.msgs.tf2_msgs.msg import TFMessage
from ros2lite.node import Node
from ros2lite.tf2 import Buffer, TransformException, TransformListener
from ros2lite.tf2.qos import TF_STATIC_TOPIC, TF_TOPIC, dynamic_listener_qos, static_listener_qos
from ros2lite.time import Time

if TYPE_CHECKING:
    from ros2lite.context import Context

_AUTHORITY = '<no authority available>'  # what tf2_ros's monitor reports: rmw carries none
_KEEP = 1000  # delays kept per frame and per broadcaster
_TICK = 0.5
_TICKS_PER_REPORT = 21
_LOWPASS = 0.01


def _num(value: float) -> str:
    """A double as a C++ stream prints it by default (6 significant digits)."""
    return f'{value:g}'


def _seconds(stamp: object) -> float:
    return getattr(stamp, 'sec', 0) + getattr(stamp, 'nanosec', 0) * 1e-9


class Tf2Monitor(Node):
    """Records the delay of every transform received, and reports it periodically."""

    def __init__(
        self, frame_a: str = '', frame_b: str = '', *, context: Context | None = None
    ) -> None:
        super().__init__('tf2_monitor_main', context=context)
        self.frame_a, self.frame_b = frame_a, frame_b
        self.specific = bool(frame_a)
        self.buffer = Buffer(node=self)
        self.listener = TransformListener(self.buffer, self, spin_thread=True)
        self.chain: list[str] = []
        self.frame_delays: dict[str, deque[float]] = {}
        self.authority_delays: dict[str, deque[float]] = {}
        self.authority_arrivals: dict[str, deque[float]] = {}
        self.max_diff = 0.0
        self.avg_diff = 0.0
        self.counter = 0
        self.gathering = False
        self.create_subscription(TFMessage, TF_TOPIC, self.on_message, dynamic_listener_qos())
        self.create_subscription(TFMessage, TF_STATIC_TOPIC, self.on_message, static_listener_qos())
        self.timer = self.create_timer(_TICK, self.tick)

    def _now(self) -> float:
        return self.get_clock().now().nanoseconds / 1e9

    def on_message(self, message: TFMessage) -> None:
        """Note each transform's delay, and the message's for its broadcaster."""
        now = self._now()
        total = 0.0
        for t in message.transforms:
            offset = now - _seconds(t.header.stamp)
            total += offset
            self.frame_delays.setdefault(t.child_frame_id, deque(maxlen=_KEEP)).append(offset)
        average = total / max(1, len(message.transforms))
        self.authority_delays.setdefault(_AUTHORITY, deque(maxlen=_KEEP)).append(average)
        self.authority_arrivals.setdefault(_AUTHORITY, deque(maxlen=_KEEP)).append(self._now())

    def _start(self) -> bool:
        """Once: wait for the two frames to connect and note the chain between them."""
        if self.specific:
            ok, why = self.buffer.can_transform_core(self.frame_a, self.frame_b, Time())
            if not ok:
                self.get_logger().info(
                    f'Waiting for transform {self.frame_a} ->  {self.frame_b}: {why}',
                    throttle_duration_sec=1.0,
                )
                return False
            try:
                self.chain = self.buffer.chain(
                    self.frame_b, Time(), self.frame_a, Time(), self.frame_b
                )
            except TransformException as e:
                self.get_logger().warning(f'Transform Exception {e}')
            print(
                f'Gathering data on {self.frame_a} -> {self.frame_b} for 10 seconds...',
                flush=True,
            )
        else:
            print('Gathering data on all frames for 10 seconds...', flush=True)
        self.gathering = True
        return True

    def tick(self) -> None:
        """Sample the chain's delay; every 21st tick, report."""
        if not self.gathering and not self._start():
            return
        self.counter += 1
        if self.specific:
            try:
                t = self.buffer.lookup_transform(self.frame_a, self.frame_b, Time())
            except TransformException as e:
                self.get_logger().warning(str(e))
            else:
                diff = self._now() - _seconds(t.header.stamp)
                self.avg_diff = _LOWPASS * diff + (1 - _LOWPASS) * self.avg_diff
                self.max_diff = max(self.max_diff, diff)
        if self.counter > _TICKS_PER_REPORT - 1:
            self.counter = 0
            self.report()

    def report(self) -> None:
        """The periodic report (its broadcaster list on stderr, as tf2_ros prints it)."""
        out = ['', '', '']
        if self.specific:
            out.append(f'RESULTS: for {self.frame_a} to {self.frame_b}')
            out.append('Chain is: ' + ' -> '.join(self.chain))
            out.append(f'Net delay     avg = {_num(self.avg_diff)}: max = {_num(self.max_diff)}')
        else:
            out.append('RESULTS: for all Frames')
        out += ['', 'Frames:']
        for frame in sorted(self.frame_delays):
            if self.specific and frame not in self.chain:
                continue
            delays = self.frame_delays[frame]
            average = sum(delays) / len(delays)
            out.append(
                f'Frame: {frame}, published by {_AUTHORITY}, Average Delay: {_num(average)}, '
                f'Max Delay: {_num(max(0.0, *delays))}'
            )
        print('\n'.join(out), flush=True)
        print('\nAll Broadcasters:', file=sys.stderr, flush=True)
        lines = []
        for authority in sorted(self.authority_delays):
            delays = self.authority_delays[authority]
            arrivals = self.authority_arrivals[authority]
            average = sum(delays) / len(delays)
            frequency = len(arrivals) / max(0.00000001, arrivals[-1] - arrivals[0])
            lines.append(
                f'Node: {authority} {_num(frequency)} Hz, Average Delay: {_num(average)} '
                f'Max Delay: {_num(max(0.0, *delays))}'
            )
        if lines:
            print('\n'.join(lines), flush=True)


def main(args: list[str] | None = None) -> int:
    """`tf2_monitor`'s entry point."""
    argv = own_arguments(args)
    if len(argv) not in (0, 2):
        from ros2lite.logging import get_logger

        get_logger('tf2_monitor_main').info('TF_Monitor: usage: tf2_monitor framea frameb')
        return 255
    return run_node(lambda: Tf2Monitor(*argv), args)


if __name__ == '__main__':
    sys.exit(main())
