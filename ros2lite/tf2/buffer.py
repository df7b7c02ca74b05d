"""tf2_ros's transform buffer: tf2's `BufferCore` (`core`) plus waiting with a timeout, futures
that resolve when a transform arrives, the `tf2_frames` service of a node, and clearing on a
jump back in time.
"""

from __future__ import annotations

import threading
import time as _time
from collections.abc import Callable
from typing import TYPE_CHECKING, Literal, overload

from ros2lite.clock import Clock, JumpThreshold
from ros2lite.duration import Duration
from ros2lite.logging import get_logger
from ros2lite.msgs.geometry_msgs.msg import TransformStamped
from ros2lite.msgs.tf2_msgs.srv import FrameGraph
from ros2lite.task import Future
from ros2lite.tf2.core import BufferCore

if TYPE_CHECKING:
    from ros2lite.clock import TimeJump
    from ros2lite.node import Node

__all__ = ['Buffer']


def _timeout_ns(timeout: object) -> int:
    if timeout is None:
        return 0
    ns = getattr(timeout, 'nanoseconds', None)
    if isinstance(ns, int):
        return ns
    raise TypeError(f'expected a Duration timeout, got {type(timeout).__name__}')


class Buffer(BufferCore):
    """tf2_ros's Buffer: a BufferCore to wait on, with the `tf2_frames` service when given a
    node, cleared when the node's clock jumps back by a second or more (a bag looping)."""

    def __init__(self, cache_time: Duration | None = None, node: Node | None = None) -> None:
        super().__init__(cache_time)
        self._changed = threading.Condition(threading.Lock())
        self._waiting = 0
        self._new_data_callbacks: list[Callable[[], None]] = []
        self._callbacks_lock = threading.RLock()
        self.clock: Clock
        if node is not None:
            self.srv = node.create_service(FrameGraph, 'tf2_frames', self._get_frames)
            self.clock = node.get_clock()
        else:
            self.clock = Clock()
        threshold = JumpThreshold(
            min_forward=None, min_backward=Duration(seconds=-1), on_clock_change=True
        )
        self.jump_handle = self.clock.create_jump_callback(
            threshold, post_callback=self.time_jump_callback
        )

    def _get_frames(
        self, request: FrameGraph.Request, response: FrameGraph.Response
    ) -> FrameGraph.Response:
        response.frame_yaml = self.all_frames_as_yaml()
        return response

    def time_jump_callback(self, time_jump: TimeJump) -> None:
        """Time went back: the history no longer lines up with the clock."""
        get_logger('tf2_buffer').warning('Detected jump back in time. Clearing tf buffer.')
        self.clear()

    def _new_data(self) -> None:
        if self._waiting:
            with self._changed:
                self._changed.notify_all()
        if self._new_data_callbacks:
            with self._callbacks_lock:
                for callback in list(self._new_data_callbacks):
                    callback()

    def _wait(self, ready: Callable[[], bool], timeout: object) -> None:
        """Block until `ready()` or the timeout (wall time) has passed."""
        ns = _timeout_ns(timeout)
        if ns <= 0 or ready():
            return
        deadline = _time.monotonic() + ns / 1e9
        with self._changed:
            self._waiting += 1
            try:
                while not ready():
                    left = deadline - _time.monotonic()
                    if left <= 0:
                        return
                    self._changed.wait(min(left, 0.1))
            finally:
                self._waiting -= 1

    def lookup_transform(
        self,
        target_frame: str,
        source_frame: str,
        time: object,
        timeout: Duration | None = None,
    ) -> TransformStamped:
        """The transform from source_frame into target_frame at `time` (Time() for the
        latest), waiting up to `timeout` for it to arrive."""
        self.can_transform(target_frame, source_frame, time, timeout)
        return self.lookup_transform_core(target_frame, source_frame, time)

    def lookup_transform_full(
        self,
        target_frame: str,
        target_time: object,
        source_frame: str,
        source_time: object,
        fixed_frame: str,
        timeout: Duration | None = None,
    ) -> TransformStamped:
        """Source at source_time into target at target_time, through `fixed_frame`."""
        self.can_transform_full(
            target_frame, target_time, source_frame, source_time, fixed_frame, timeout
        )
        return self.lookup_transform_full_core(
            target_frame, target_time, source_frame, source_time, fixed_frame
        )

    @overload
    def can_transform(
        self,
        target_frame: str,
        source_frame: str,
        time: object,
        timeout: Duration | None = None,
        return_debug_tuple: Literal[False] = False,
    ) -> bool: ...

    @overload
    def can_transform(
        self,
        target_frame: str,
        source_frame: str,
        time: object,
        timeout: Duration | None,
        return_debug_tuple: Literal[True],
    ) -> tuple[bool, str]: ...

    @overload
    def can_transform(
        self,
        target_frame: str,
        source_frame: str,
        time: object,
        timeout: Duration | None = None,
        *,
        return_debug_tuple: Literal[True],
    ) -> tuple[bool, str]: ...

    def can_transform(
        self,
        target_frame: str,
        source_frame: str,
        time: object,
        timeout: Duration | None = None,
        return_debug_tuple: bool = False,
    ) -> bool | tuple[bool, str]:
        """Whether the lookup can be made, waiting up to `timeout`; with
        `return_debug_tuple`, (whether, why not)."""
        self._wait(lambda: self.can_transform_core(target_frame, source_frame, time)[0], timeout)
        result = self.can_transform_core(target_frame, source_frame, time)
        return result if return_debug_tuple else result[0]

    @overload
    def can_transform_full(
        self,
        target_frame: str,
        target_time: object,
        source_frame: str,
        source_time: object,
        fixed_frame: str,
        timeout: Duration | None = None,
        return_debug_tuple: Literal[False] = False,
    ) -> bool: ...

    @overload
    def can_transform_full(
        self,
        target_frame: str,
        target_time: object,
        source_frame: str,
        source_time: object,
        fixed_frame: str,
        timeout: Duration | None,
        return_debug_tuple: Literal[True],
    ) -> tuple[bool, str]: ...

    @overload
    def can_transform_full(
        self,
        target_frame: str,
        target_time: object,
        source_frame: str,
        source_time: object,
        fixed_frame: str,
        timeout: Duration | None = None,
        *,
        return_debug_tuple: Literal[True],
    ) -> tuple[bool, str]: ...

    def can_transform_full(
        self,
        target_frame: str,
        target_time: object,
        source_frame: str,
        source_time: object,
        fixed_frame: str,
        timeout: Duration | None = None,
        return_debug_tuple: bool = False,
    ) -> bool | tuple[bool, str]:
        """As `can_transform`, for the full lookup."""
        args = (target_frame, target_time, source_frame, source_time, fixed_frame)
        self._wait(lambda: self.can_transform_full_core(*args)[0], timeout)
        result = self.can_transform_full_core(*args)
        return result if return_debug_tuple else result[0]

    def _future(
        self, ready: Callable[[], bool], lookup: Callable[[], TransformStamped]
    ) -> Future[TransformStamped]:
        future: Future[TransformStamped] = Future()

        def on_new_data() -> None:
            if future.done():
                return
            try:
                if ready():
                    future.set_result(lookup())
            except Exception as e:  # the caller's to see, never the listener thread's
                future.set_exception(e)

        def forget(_: Future[TransformStamped]) -> None:
            with self._callbacks_lock:
                if on_new_data in self._new_data_callbacks:
                    self._new_data_callbacks.remove(on_new_data)

        # registered before the first look, so a transform stored in between (by the
        # listener's thread) still completes the future: a static one never comes again
        with self._callbacks_lock:
            self._new_data_callbacks.append(on_new_data)
        future.add_done_callback(forget)
        with self._callbacks_lock:  # one completion at a time (_new_data holds it too)
            on_new_data()
        return future

    def wait_for_transform_async(
        self, target_frame: str, source_frame: str, time: object
    ) -> Future[TransformStamped]:
        """A future that completes with the transform once it can be looked up."""
        return self._future(
            lambda: self.can_transform_core(target_frame, source_frame, time)[0],
            lambda: self.lookup_transform_core(target_frame, source_frame, time),
        )

    def wait_for_transform_full_async(
        self,
        target_frame: str,
        target_time: object,
        source_frame: str,
        source_time: object,
        fixed_frame: str,
    ) -> Future[TransformStamped]:
        """As `wait_for_transform_async`, for the full lookup."""
        args = (target_frame, target_time, source_frame, source_time, fixed_frame)
        return self._future(
            lambda: self.can_transform_full_core(*args)[0],
            lambda: self.lookup_transform_full_core(*args),
        )

    async def lookup_transform_async(
        self, target_frame: str, source_frame: str, time: object
    ) -> TransformStamped:
        """Await the transform (in a coroutine run by an executor)."""
        await self.wait_for_transform_async(target_frame, source_frame, time)
        return self.lookup_transform_core(target_frame, source_frame, time)

    async def lookup_transform_full_async(
        self,
        target_frame: str,
        target_time: object,
        source_frame: str,
        source_time: object,
        fixed_frame: str,
    ) -> TransformStamped:
        """Await the full transform."""
        args = (target_frame, target_time, source_frame, source_time, fixed_frame)
        await self.wait_for_transform_full_async(*args)
        return self.lookup_transform_full_core(*args)
