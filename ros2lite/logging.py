"""Node loggers: rcutils' console format on stderr, and `/rosout` messages.

Format follows RCUTILS_CONSOLE_OUTPUT_FORMAT (default `[{severity}] [{time}] [{name}]: {message}`);
RCUTILS_LOGGING_USE_STDOUT=1 moves output to stdout, RCUTILS_COLORIZED_OUTPUT=1 adds colour.
"""

from __future__ import annotations

import inspect
import os
import sys
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, TypedDict

if TYPE_CHECKING:
    from typing_extensions import Unpack


class LogOptions(TypedDict, total=False):
    """The keyword options of the level methods (rclpy's)."""

    once: bool
    skip_first: bool
    throttle_duration_sec: float | None
    throttle_time_source_type: object  # accepted and ignored, as in rclpy without a clock


DEBUG, INFO, WARN, ERROR, FATAL = 10, 20, 30, 40, 50
_NAMES = {DEBUG: 'DEBUG', INFO: 'INFO', WARN: 'WARN', ERROR: 'ERROR', FATAL: 'FATAL'}
_COLORS = {DEBUG: '\033[32m', INFO: '', WARN: '\033[33m', ERROR: '\033[31m', FATAL: '\033[31m'}
DEFAULT_FORMAT = '[{severity}] [{time}] [{name}]: {message}'

# logger name → level set by --log-level or set_level; None key is the default level
_levels: dict[str | None, int] = {None: INFO}


def set_logger_level(name: str | None, level: int) -> None:
    """The level of logger `name` and its children (None: the default level)."""
    _levels[name] = level


def get_logger_level(name: str) -> int:
    """The level that applies to `name`: its own, its nearest parent's, or the default."""
    while name:
        if name in _levels:
            return _levels[name]
        name = name.rpartition('.')[0]
    return _levels[None]


def _format(
    severity: int, name: str, message: str, stamp_ns: int, caller: inspect.Traceback
) -> str:
    fmt = os.environ.get('RCUTILS_CONSOLE_OUTPUT_FORMAT', DEFAULT_FORMAT)
    sec, nsec = divmod(stamp_ns, 1_000_000_000)
    fields = {
        'severity': _NAMES[severity],
        'name': name,
        'message': message,
        'time': f'{sec}.{nsec:09d}',
        'time_as_nanoseconds': str(stamp_ns),
        'function_name': caller.function,
        'file_name': caller.filename,
        'line_number': str(caller.lineno),
    }
    if '{date_time_with_ms}' in fmt:  # the only costly field: only when asked for
        fields['date_time_with_ms'] = (
            time.strftime('%Y-%m-%d %H:%M:%S', time.localtime(sec)) + f'.{nsec // 1_000_000:03d}'
        )
    text = fmt
    for key, value in fields.items():
        text = text.replace('{' + key + '}', value)
    return text


class RcutilsLogger:
    """rclpy-compatible logger: debug/info/warn/error/fatal with once/skip_first/throttle."""

    def __init__(
        self,
        name: str = '',
        publish: Callable[[int, str, str, inspect.Traceback], None] | None = None,
    ) -> None:
        self.name = name
        self._publish = publish
        self._once: set[tuple[str, int]] = set()
        self._seen: set[tuple[str, int]] = set()
        self._last: dict[tuple[str, int], float] = {}

    def get_child(self, suffix: str) -> RcutilsLogger:
        """A logger named `<this>.<suffix>` (publishing where this one does)."""
        return RcutilsLogger(f'{self.name}.{suffix}' if self.name else suffix, self._publish)

    def set_level(self, level: int) -> None:
        """Set this logger's level (and its children's, unless they have their own)."""
        set_logger_level(self.name, int(level))

    def get_effective_level(self) -> int:
        """The level that applies to this logger."""
        return get_logger_level(self.name)

    def is_enabled_for(self, severity: int) -> bool:
        """Whether a message of `severity` would be logged."""
        return severity >= self.get_effective_level()

    def log(
        self,
        message: object,
        severity: int,
        *,
        once: bool = False,
        skip_first: bool = False,
        throttle_duration_sec: float | None = None,
        **_: object,  # rclpy's other options (e.g. throttle_time_source_type) are ignored
    ) -> bool:
        """Print `str(message)` at `severity` (and publish it on /rosout for a node's
        logger) unless the level, `once`, `skip_first` or the throttle hold it back; True
        when it was logged."""
        if not self.is_enabled_for(severity):
            return False
        # the user's frame, found directly: inspect.stack() walked (and described) the whole
        # stack on every call, which made one log line cost 0.3-2 ms
        frame = sys._getframe(1)
        if frame.f_code in _LEVEL_METHODS and frame.f_back is not None:
            frame = frame.f_back  # called through debug()/info()/…
        code = frame.f_code
        caller = inspect.Traceback(code.co_filename, frame.f_lineno, code.co_name, None, None)
        site = (code.co_filename, frame.f_lineno)
        if once:
            if site in self._once:
                return False
            self._once.add(site)
        if skip_first and site not in self._seen:
            self._seen.add(site)
            return False
        if throttle_duration_sec:
            now = time.monotonic()
            if now - self._last.get(site, -1e18) < throttle_duration_sec:
                return False
            self._last[site] = now
        text = str(message)
        stamp = time.time_ns()
        line = _format(severity, self.name, text, stamp, caller)
        stream = sys.stdout if os.environ.get('RCUTILS_LOGGING_USE_STDOUT') == '1' else sys.stderr
        if os.environ.get('RCUTILS_COLORIZED_OUTPUT') == '1' and _COLORS[severity]:
            line = f'{_COLORS[severity]}{line}\033[0m'
        print(line, file=stream, flush=True)
        if self._publish is not None:
            self._publish(severity, self.name, text, caller)
        return True

    def debug(self, message: object, **kw: Unpack[LogOptions]) -> bool:
        """log() at DEBUG."""
        return self.log(message, DEBUG, **kw)

    def info(self, message: object, **kw: Unpack[LogOptions]) -> bool:
        """log() at INFO."""
        return self.log(message, INFO, **kw)

    def warn(self, message: object, **kw: Unpack[LogOptions]) -> bool:
        """log() at WARN."""
        return self.log(message, WARN, **kw)

    warning = warn

    def error(self, message: object, **kw: Unpack[LogOptions]) -> bool:
        """log() at ERROR."""
        return self.log(message, ERROR, **kw)

    def fatal(self, message: object, **kw: Unpack[LogOptions]) -> bool:
        """log() at FATAL."""
        return self.log(message, FATAL, **kw)


_LEVEL_METHODS = {
    f.__code__
    for f in (
        RcutilsLogger.debug,
        RcutilsLogger.info,
        RcutilsLogger.warn,
        RcutilsLogger.error,
        RcutilsLogger.fatal,
    )
}


def get_logger(name: str) -> RcutilsLogger:
    """A console-only logger (no node, so nothing goes to /rosout)."""
    return RcutilsLogger(name)
