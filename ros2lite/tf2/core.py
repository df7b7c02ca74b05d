"""tf2's BufferCore (tf2_py's Python names): frames by id, a cache of each one's recent history,
the walk from both frames up to their common ancestor, Time(0) as the latest time the whole
chain shares, tf2's errors and its texts. `buffer.Buffer` adds tf2_ros's waiting on it."""

from __future__ import annotations

import threading
from collections.abc import Iterator

from ros2lite.duration import Duration
from ros2lite.logging import RcutilsLogger
from ros2lite.msgs.builtin_interfaces.msg import Time as TimeMsg
from ros2lite.msgs.geometry_msgs.msg import Quaternion, TransformStamped, Vector3
from ros2lite.msgs.geometry_msgs.msg import Transform as TransformMsg
from ros2lite.msgs.std_msgs.msg import Header
from ros2lite.tf2.cache import (
    CacheError,
    FrameCache,
    Sample,
    StaticCache,
    TimeCache,
    display_time,
    to_seconds,
)
from ros2lite.tf2.errors import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
)
from ros2lite.tf2.math import IDENTITY, Transform, compose, inverse
from ros2lite.time import Time
from ros2lite.util.safe_yaml import yaml_key, yaml_text

__all__ = ['DEFAULT_CACHE_TIME', 'BufferCore']

DEFAULT_CACHE_TIME = Duration(seconds=10)
"""How far back a buffer keeps a moving frame's history, as tf2's default."""

_MAX_GRAPH_DEPTH = 1000
_NORMALIZATION_TOLERANCE = 10e-3  # |q|^2 may be this far from 1 (tf2's tolerance)
_NS = 1_000_000_000

# outcomes of a walk besides a cache's own errors
_CONNECTIVITY = 10
_LOOKUP = 11

# tf2's core reports refused data through rcutils' unnamed logger: `[WARN] [time] []: ...`
_log = RcutilsLogger()


def to_ns(time: object) -> int:
    """Nanoseconds of a time given as rclpy's Time, a builtin_interfaces Time message or a
    number of nanoseconds; 0 means "the latest"."""
    if isinstance(time, int):
        return time
    ns = getattr(time, 'nanoseconds', None)
    if isinstance(ns, int):
        return ns
    sec = getattr(time, 'sec', None)
    if isinstance(sec, int):
        return sec * _NS + int(getattr(time, 'nanosec', 0))
    raise TypeError(f'expected a Time, got {type(time).__name__}')


def _hop(
    cache: FrameCache, ns: int, with_transform: bool
) -> tuple[Sample | None, int, CacheError | None, str]:
    """One step of a walk up from a frame at `ns`: (its sample, only when the transform is
    wanted, its parent, a cache error, its text)."""
    if with_transform:
        sample, error, message = cache.get(ns)
        return sample, sample[0] if sample is not None else 0, error, message
    parent, error, message = cache.parent(ns)
    return None, parent, error, message


def _raise(code: int, message: str) -> None:
    if code == _CONNECTIVITY:
        raise ConnectivityException(message)
    if code == _LOOKUP:
        raise LookupException(message)
    raise ExtrapolationException(message)


class BufferCore:
    """Frames and their histories; lookups between any two frames of a tree, at a time."""

    def __init__(self, cache_time: Duration | None = None) -> None:
        self._cache_ns = (cache_time or DEFAULT_CACHE_TIME).nanoseconds
        self._lock = threading.RLock()
        self._ids: dict[str, int] = {'NO_PARENT': 0}
        self._names: list[str] = ['NO_PARENT']
        self._caches: list[FrameCache | None] = [None]
        self._authority: dict[int, str] = {}

    # -- storing ------------------------------------------------------------------------------
    def set_transform(self, transform: TransformStamped, authority: str) -> bool:
        """Add a transform of a moving frame; False (logged) when tf2 would refuse it."""
        return self._store(transform, authority, False)

    def set_transform_static(self, transform: TransformStamped, authority: str) -> bool:
        """Add (or replace) the transform of a frame that never moves."""
        return self._store(transform, authority, True)

    def _store(self, msg: TransformStamped, authority: str, is_static: bool) -> bool:
        header = msg.header
        # tf2 drops one leading slash of either name
        parent_name = header.frame_id.removeprefix('/')
        child_name = msg.child_frame_id.removeprefix('/')
        transform = msg.transform
        t = transform.translation
        r = transform.rotation
        translation = (t.x, t.y, t.z)
        x, y, z, w = rotation = (r.x, r.y, r.z, r.w)
        total = translation[0] + translation[1] + translation[2] + x + y + z + w
        if (
            child_name == parent_name
            or not child_name
            or not parent_name
            or total != total  # a NaN somewhere (or infinities that cancel): look closer
            or not abs(w * w + x * x + y * y + z * z - 1.0) < _NORMALIZATION_TOLERANCE
        ) and not self._valid(parent_name, child_name, authority, translation, rotation):
            return False
        stamp = header.stamp
        ns = stamp.sec * _NS + stamp.nanosec
        with self._lock:
            child = self._ids.get(child_name) or self._id_of(child_name)
            cache = self._caches[child]
            if cache is None or isinstance(cache, StaticCache) != is_static:
                cache = StaticCache() if is_static else TimeCache(self._cache_ns)
                self._caches[child] = cache
            parent = self._ids.get(parent_name) or self._id_of(parent_name)
            if not cache.insert(ns, parent, translation, rotation):
                _log.warning(
                    f'TF_OLD_DATA ignoring data from the past for frame {child_name} at time '
                    f'{display_time(ns)} according to authority {authority}\nPossible reasons '
                    'are listed at http://wiki.ros.org/tf/Errors%20explained'
                )
                return False
            self._authority[child] = authority
        self._new_data()
        return True

    def _valid(
        self,
        parent: str,
        child: str,
        authority: str,
        translation: tuple[float, float, float],
        rotation: tuple[float, float, float, float],
    ) -> bool:
        ok = True
        if child == parent:
            _log.error(
                f'TF_SELF_TRANSFORM: Ignoring transform from authority "{authority}" with '
                f'frame_id and  child_frame_id "{child}" because they are the same'
            )
            ok = False
        if not child:
            _log.error(
                f'TF_NO_CHILD_FRAME_ID: Ignoring transform from authority "{authority}" '
                'because child_frame_id not set '
            )
            ok = False
        if not parent:
            _log.error(
                f'TF_NO_FRAME_ID: Ignoring transform with child_frame_id "{child}"  from '
                f'authority "{authority}" because frame_id not set'
            )
            ok = False
        values = (*translation, *rotation)
        if any(v != v for v in values):
            _log.error(
                f'TF_NAN_INPUT: Ignoring transform for child_frame_id "{child}" from authority '
                f'"{authority}" because of a nan value in the transform '
                '({:f} {:f} {:f}) ({:f} {:f} {:f} {:f})'.format(*values)
            )
            ok = False
        x, y, z, w = rotation
        if not abs(w * w + x * x + y * y + z * z - 1.0) < _NORMALIZATION_TOLERANCE:
            _log.error(
                f'TF_DENORMALIZED_QUATERNION: Ignoring transform for child_frame_id "{child}" '
                f'from authority "{authority}" because of an invalid quaternion in the '
                'transform ({:f} {:f} {:f} {:f})'.format(*rotation)
            )
            ok = False
        return ok

    def _id_of(self, name: str) -> int:
        """The id of a frame, made on first mention (as a child or as a parent)."""
        frame = self._ids.get(name)
        if frame is None:
            frame = len(self._names)
            self._ids[name] = frame
            self._names.append(name)
            self._caches.append(None)
        return frame

    def _new_data(self) -> None:
        """Hook for `Buffer`: something was stored."""

    def clear(self) -> None:
        """Forget the history of every moving frame (static frames stay, as in tf2)."""
        with self._lock:
            for cache in self._caches:
                if cache is not None:
                    cache.clear()

    # -- frames -------------------------------------------------------------------------------
    def _validate(self, function: str, frame_id: str) -> int:
        """The id of an existing frame, or tf2's exception for the argument."""
        if not frame_id:
            raise InvalidArgumentException(
                f'Invalid argument "{frame_id}" passed to {function} - in tf2 frame_ids '
                'cannot be empty'
            )
        if frame_id.startswith('/'):
            raise InvalidArgumentException(
                f'Invalid argument "{frame_id}" passed to {function} - in tf2 frame_ids '
                "cannot start with a '/'"
            )
        frame = self._ids.get(frame_id, 0)
        if frame == 0:
            raise LookupException(f'"{frame_id}" passed to {function} does not exist. ')
        return frame

    def _check(self, function: str, frame_id: str) -> tuple[int, str]:
        """As `_validate`, but (0, why) instead of raising (tf2's can_transform texts)."""
        if not frame_id:
            why = 'in tf2 frame_ids cannot be empty'
        elif frame_id.startswith('/'):
            why = "in tf2 frame_ids cannot start with a '/'"
        else:
            frame = self._ids.get(frame_id, 0)
            if frame:
                return frame, ''
            why = 'frame does not exist'
        return 0, f'Invalid frame ID "{frame_id}" passed to {function} - {why}'

    def _frameExists(self, frame_id: str) -> bool:
        """Whether the buffer has heard of the frame."""
        with self._lock:
            return frame_id in self._ids and frame_id != 'NO_PARENT'

    def _getFrameStrings(self) -> list[str]:
        """Every frame the buffer has heard of, roots (bare parents) too, as tf2 lists them."""
        with self._lock:
            return self._names[1:]

    # -- the walk -----------------------------------------------------------------------------
    def _walk(
        self, target: int, source: int, ns: int, with_transform: bool
    ) -> tuple[int, str, Transform, int]:
        """Walk source and target up to their common ancestor at `ns` (0: the latest common
        time). Returns (0 or an error code, error text, the transform source -> target, the
        time used). Called with the lock held."""
        if source == target:
            return 0, '', IDENTITY, ns
        if ns == 0:
            code, message, ns = self._latest_common_time(target, source)
            if code:
                return code, message, IDENTITY, ns
        caches = self._caches
        # from the source up, accumulating source -> top
        frame = source
        top = frame
        source_to_top = IDENTITY
        extrapolation: tuple[int, str] | None = None
        depth = 0
        while frame != 0:
            cache = caches[frame]
            if cache is None:  # the root of a tree has no transform of its own
                top = frame
                break
            sample, parent, error, message = _hop(cache, ns, with_transform)
            if error is not None:  # a target further down may still be reached
                top = frame
                extrapolation = (int(error), message)
                break
            if frame == target:  # the target is an ancestor of the source
                return 0, '', source_to_top, ns
            if sample is not None:
                source_to_top = compose((sample[1], sample[2]), source_to_top)
            top = frame
            frame = parent
            depth += 1
            if depth > _MAX_GRAPH_DEPTH:
                return _LOOKUP, self._loop_message(), IDENTITY, ns
        # from the target up to the same top, accumulating target -> top
        frame = target
        target_to_top = IDENTITY
        depth = 0
        while frame != top:
            cache = caches[frame]
            if cache is None:
                break
            sample, parent, error, message = _hop(cache, ns, with_transform)
            if error is not None:
                return int(error), self._between(message, source, target), IDENTITY, ns
            if frame == source:  # the source is an ancestor of the target
                return 0, '', inverse(target_to_top), ns
            if sample is not None:
                target_to_top = compose((sample[1], sample[2]), target_to_top)
            frame = parent
            depth += 1
            if depth > _MAX_GRAPH_DEPTH:
                return _LOOKUP, self._loop_message(), IDENTITY, ns
        if frame != top:
            if extrapolation is not None:
                code, message = extrapolation
                return code, self._between(message, source, target), IDENTITY, ns
            return _CONNECTIVITY, self._disconnected(source, target), IDENTITY, ns
        if not with_transform:
            return 0, '', IDENTITY, ns
        return 0, '', compose(inverse(target_to_top), source_to_top), ns

    def _between(self, message: str, source: int, target: int) -> str:
        return (
            f'{message}, when looking up transform from frame [{self._names[source]}] '
            f'to frame [{self._names[target]}]'
        )

    def _disconnected(self, source: int, target: int) -> str:
        return (
            f"Could not find a connection between '{self._names[target]}' and "
            f"'{self._names[source]}' because they are not part of the same tree."
            'Tf has two or more unconnected trees.'
        )

    def _loop_message(self) -> str:
        return (
            f'The tf tree is invalid because it contains a loop.\n{self.all_frames_as_string()}\n'
        )

    def _latest_common_time(self, target: int, source: int) -> tuple[int, str, int]:
        """The newest time at which every frame between the two has data (0 when the chain
        is all static); tf2's getLatestCommonTime."""
        caches = self._caches
        if source == target:
            cache = caches[source]
            return 0, '', cache.latest()[0] if cache is not None else 0
        chain: list[tuple[int, int]] = []  # (stamp, parent) from the source up
        never = 1 << 63
        common = never
        for depth, (stamp, parent) in enumerate(self._latest_links(source)):
            if stamp != 0:
                common = min(common, stamp)
            chain.append((stamp, parent))
            if parent == target:
                return 0, '', 0 if common == never else common
            if depth >= _MAX_GRAPH_DEPTH:
                return _LOOKUP, self._loop_message(), 0
        common = never
        common_parent = 0
        parents = {parent for _, parent in chain}
        for depth, (stamp, parent) in enumerate(self._latest_links(target)):
            if stamp != 0:
                common = min(common, stamp)
            if parent in parents:
                common_parent = parent
                break
            if parent == source:
                return 0, '', 0 if common == never else common
            if depth >= _MAX_GRAPH_DEPTH:
                return _LOOKUP, self._loop_message(), 0
        if common_parent == 0:
            return _CONNECTIVITY, self._disconnected(source, target), 0
        for stamp, parent in chain:
            if stamp != 0:
                common = min(common, stamp)
            if parent == common_parent:
                break
        return 0, '', 0 if common == never else common

    def _latest_links(self, frame: int) -> Iterator[tuple[int, int]]:
        """(newest stamp, parent) of each frame from `frame` up, while the frame has a
        transform of its own (lock held)."""
        caches = self._caches
        while frame != 0:
            cache = caches[frame]
            if cache is None:
                return
            stamp, parent = cache.latest()
            if parent == 0:
                return
            yield stamp, parent
            frame = parent

    # -- lookups (tf2_py's names) -------------------------------------------------------------
    def lookup(self, target_frame: str, source_frame: str, ns: int) -> tuple[Transform, int]:
        """The transform taking source_frame coordinates into target_frame at `ns` (0: the
        latest common time), and the time it holds at; tf2's exceptions when there is none."""
        with self._lock:
            if target_frame == source_frame:
                if ns == 0:
                    frame = self._ids.get(target_frame, 0)
                    cache = self._caches[frame]
                    ns = cache.latest()[0] if cache is not None else 0
                return IDENTITY, ns
            target = self._validate('lookupTransform argument target_frame', target_frame)
            source = self._validate('lookupTransform argument source_frame', source_frame)
            code, message, transform, used = self._walk(target, source, ns, True)
        if code:
            _raise(code, message)
        return transform, used

    def lookup_transform_core(
        self, target_frame: str, source_frame: str, time: object
    ) -> TransformStamped:
        """tf2_py's lookup: no waiting, the transform or an exception."""
        transform, ns = self.lookup(target_frame, source_frame, to_ns(time))
        return _message(target_frame, source_frame, transform, ns)

    def lookup_full(
        self,
        target_frame: str,
        target_ns: int,
        source_frame: str,
        source_ns: int,
        fixed_frame: str,
    ) -> tuple[Transform, int]:
        """Source at `source_ns` into target at `target_ns`, through a frame fixed in time."""
        with self._lock:
            self._validate('lookupTransform argument target_frame', target_frame)
            self._validate('lookupTransform argument source_frame', source_frame)
            self._validate('lookupTransform argument fixed_frame', fixed_frame)
        source_to_fixed, _ = self.lookup(fixed_frame, source_frame, source_ns)
        fixed_to_target, ns = self.lookup(target_frame, fixed_frame, target_ns)
        return compose(fixed_to_target, source_to_fixed), ns

    def lookup_transform_full_core(
        self,
        target_frame: str,
        target_time: object,
        source_frame: str,
        source_time: object,
        fixed_frame: str,
    ) -> TransformStamped:
        """tf2_py's full lookup: no waiting."""
        transform, ns = self.lookup_full(
            target_frame, to_ns(target_time), source_frame, to_ns(source_time), fixed_frame
        )
        return _message(target_frame, source_frame, transform, ns)

    def _can(self, target_frame: str, source_frame: str, ns: int, prefix: str) -> tuple[bool, str]:
        if target_frame == source_frame:
            return True, ''
        with self._lock:
            target, why = self._check(f'{prefix} argument target_frame', target_frame)
            if not target:
                return False, why
            source, why = self._check(f'{prefix} argument source_frame', source_frame)
            if not source:
                return False, why
            code, message, _, _ = self._walk(target, source, ns, False)
        return code == 0, message

    def can_transform_core(
        self, target_frame: str, source_frame: str, time: object
    ) -> tuple[bool, str]:
        """(whether the lookup would succeed now, why not)."""
        return self._can(target_frame, source_frame, to_ns(time), 'canTransform')

    def can_transform_full_core(
        self,
        target_frame: str,
        target_time: object,
        source_frame: str,
        source_time: object,
        fixed_frame: str,
    ) -> tuple[bool, str]:
        """(whether the full lookup would succeed now, why not)."""
        with self._lock:
            for name, frame_id in (
                ('target_frame', target_frame),
                ('source_frame', source_frame),
                ('fixed_frame', fixed_frame),
            ):
                found, why = self._check(f'canTransform argument {name}', frame_id)
                if not found:
                    return False, why
        ok, why = self._can(target_frame, fixed_frame, to_ns(target_time), 'canTransform')
        if not ok:
            return ok, why
        return self._can(fixed_frame, source_frame, to_ns(source_time), 'canTransform')

    def get_latest_common_time(self, target_frame: str, source_frame: str) -> Time:
        """The newest time a lookup between the two frames can use."""
        with self._lock:
            target = self._validate('get_latest_common_time', target_frame)
            source = self._validate('get_latest_common_time', source_frame)
            code, message, ns = self._latest_common_time(target, source)
        if code:
            _raise(code, message)
        return Time(nanoseconds=ns)

    def chain(
        self,
        target_frame: str,
        target_time: object,
        source_frame: str,
        source_time: object,
        fixed_frame: str,
    ) -> list[str]:
        """The frames from source to target through the fixed frame (tf2's _chainAsVector)."""
        with self._lock:
            target = self._validate('chainAsVector argument target_frame', target_frame)
            source = self._validate('chainAsVector argument source_frame', source_frame)
            fixed = self._validate('chainAsVector argument fixed_frame', fixed_frame)
            first = self._path(fixed, source, to_ns(source_time))
            second = self._path(target, fixed, to_ns(target_time))
        if first and second and first[-1] == second[0]:
            second = second[1:]
        return [self._names[f] for f in first + second]

    _chain = chain  # tf2_py's name

    def _path(self, target: int, source: int, ns: int) -> list[int]:
        """The frames a walk passes from source to target (lock held)."""
        if source == target:
            return [source]
        code, message, _, ns = self._walk(target, source, ns, False)
        if code:
            _raise(code, message)
        up: list[int] = []
        frame = source
        while True:
            up.append(frame)
            if frame == target:
                return up
            cache = self._caches[frame]
            if cache is None:
                break
            frame = cache.parent(ns)[0]
            if frame == 0 or len(up) > _MAX_GRAPH_DEPTH:
                break
        down: list[int] = []
        frame = target
        while frame not in up:
            down.append(frame)
            cache = self._caches[frame]
            if cache is None:
                break
            frame = cache.parent(ns)[0]
        return up[: up.index(frame) + 1] + down[::-1] if frame in up else up + down[::-1]

    # -- the tree as text ---------------------------------------------------------------------
    def all_frames_as_string(self) -> str:
        """One line per frame: 'Frame child exists with parent parent.' (tf2's text)."""
        return ''.join(
            f'Frame {c} exists with parent {p}.\n' for c, p in self.frame_parents().items()
        )

    def frame_parents(self) -> dict[str, str]:
        """Each frame's parent by name, as that text says it (for views that walk the tree)."""
        with self._lock:
            names = self._names
            got = ((names[f], c.get(0)[0]) for f, c in enumerate(self._caches) if c is not None)
            return {child: names[s[0] if s is not None else 0] for child, s in got}

    def all_frames_as_yaml(self, current_time: object = None) -> str:
        """Each frame's parent, broadcaster, rate and span in tf2's YAML (view_frames' text)."""
        now = to_ns(current_time) if current_time is not None else 0
        out: list[str] = []
        with self._lock:
            if len(self._names) == 1:
                return '[]'
            for frame, cache in enumerate(self._caches):
                if cache is None:
                    continue
                sample = cache.get(0)[0]
                if sample is None:
                    continue
                latest, oldest = cache.latest()[0], cache.oldest_stamp()
                span = latest - oldest
                rate = len(cache) * 1e9 / max(span, 100_000)
                out.append(yaml_key(self._names[frame]))
                out.append(f'  parent: {yaml_text(self._names[sample[0]])}\n')
                authority = self._authority.get(frame, 'no recorded authority')
                out.append(f'  broadcaster: {yaml_text(authority)}\n')
                out.append(f'  rate: {rate:.3f}\n')
                out.append(f'  most_recent_transform: {display_time(latest)}\n')
                out.append(f'  oldest_transform: {display_time(oldest)}\n')
                if now:
                    out.append(f'  transform_delay: {to_seconds(now - latest):.3f}\n')
                out.append(f'  buffer_length: {to_seconds(span):.3f}\n')
        return ''.join(out)


def _message(target: str, source: str, transform: Transform, ns: int) -> TransformStamped:
    """The lookup's answer as the message tf2 returns."""
    (x, y, z), (qx, qy, qz, qw) = transform
    return TransformStamped(
        header=Header(stamp=TimeMsg(sec=ns // _NS, nanosec=ns % _NS), frame_id=target),
        child_frame_id=source,
        transform=TransformMsg(
            translation=Vector3(x=x, y=y, z=z), rotation=Quaternion(x=qx, y=qy, z=qz, w=qw)
        ),
    )
