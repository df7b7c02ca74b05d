"""Loggers as rclpy has them: rcutils' console format on stderr, severities and a hierarchy of
logger levels, the once/skip_first/throttle filters, and `/rosout` messages for node loggers.

Format follows RCUTILS_CONSOLE_OUTPUT_FORMAT (default `[{severity}] [{time}] [{name}]: {message}`);
RCUTILS_LOGGING_USE_STDOUT=1 moves output to stdout, RCUTILS_COLORIZED_OUTPUT=1 adds colour.

Levels live in one table keyed by logger name; a logger without a level of its own takes its
nearest ancestor's (`a.b.c` → `a.b` → `a`), and the root logger's level is the default.
Filters keep their state per call site (the line that logs) and per logger object, and the
arguments of a call site may not change between calls, as in rclpy.
"""

from __future__ import annotations

import enum
import inspect
import os
import sys
import time
from collections.abc import Callable, Mapping
from pathlib import Path
from types import CodeType, FrameType
from typing import TYPE_CHECKING, Protocol, TypedDict, cast

if TYPE_CHECKING:
    from typing_extensions import Unpack

    from ros2lite.time import Time

__all__ = [
    'DEBUG',
    'ERROR',
    'FATAL',
    'INFO',
    'WARN',
    'LogOptions',
    'LoggingSeverity',
    'RcutilsLogger',
    'clear_config',
    'get_logger',
    'get_logger_effective_level',
    'get_logger_level',
    'get_logging_directory',
    'get_logging_severity_from_string',
    'set_logger_level',
]


class LoggingSeverity(enum.IntEnum):
    """rcutils' severities (the numbers on `/rosout` and in logger services)."""

    UNSET = 0
    DEBUG = 10
    INFO = 20
    WARN = 30
    ERROR = 40
    FATAL = 50


class ThrottleClock(Protocol):
    """What a throttled log reads of its clock (:class:`ros2lite.clock.Clock` is one): named
    here so that logging sits below the clocks, and so below the context."""

    def now(self) -> Time:
        """The clock's current time."""
        ...


class LogOptions(TypedDict, total=False):
    """The keyword options of `log()` and the level methods (rclpy's)."""

    once: bool
    skip_first: bool
    throttle_duration_sec: float | None
    throttle_time_source_type: ThrottleClock  # the clock the throttle reads (system time if absent)
    name: str  # log under another logger name


DEBUG, INFO, WARN, ERROR, FATAL = 10, 20, 30, 40, 50
_NAMES = {DEBUG: 'DEBUG', INFO: 'INFO', WARN: 'WARN', ERROR: 'ERROR', FATAL: 'FATAL'}
_COLORS = {DEBUG: '\033[32m', INFO: '', WARN: '\033[33m', ERROR: '\033[31m', FATAL: '\033[31m'}
DEFAULT_FORMAT = '[{severity}] [{time}] [{name}]: {message}'

# console output on/off (--disable-stdout-logs turns it off for the process, as in rcl)
_console = True


def set_console_output(enabled: bool) -> None:
    """Whether loggers print to the console (stderr, or stdout when configured so)."""
    global _console
    _console = bool(enabled)


# logger name → level set by --log-level or set_level; the None key is the default level
_DEFAULT_LEVEL = INFO
_levels: dict[str | None, int] = {None: _DEFAULT_LEVEL}


def set_logger_level(name: str | None, level: int) -> None:
    """Set a logger's level (UNSET clears it, so it follows its ancestors again); the
    empty name (or None) is the root logger, whose level is the default."""
    level = int(LoggingSeverity(level))
    if not name:
        _levels[None] = level
    elif level == LoggingSeverity.UNSET:
        _levels.pop(name, None)
    else:
        _levels[name] = level


def get_logger_effective_level(name: str | None) -> LoggingSeverity:
    """The level that decides for `name`: its own, else its nearest ancestor's, else the
    default."""
    while name:
        if name in _levels:
            return LoggingSeverity(_levels[name])
        name = name.rpartition('.')[0]
    return LoggingSeverity(_levels[None])


def get_logger_level(name: str) -> LoggingSeverity:
    """The level set for `name` itself (UNSET if none was)."""
    if not name:
        return LoggingSeverity(_levels[None])
    return LoggingSeverity(_levels.get(name, LoggingSeverity.UNSET))


def clear_config() -> None:
    """Forget every logger level (the default goes back to INFO)."""
    _levels.clear()
    _levels[None] = _DEFAULT_LEVEL


def get_logging_severity_from_string(log_severity: str) -> LoggingSeverity:
    """'info', 'WARN', … as a severity; RuntimeError for anything else."""
    key = log_severity.strip().upper()
    if key == 'WARNING':
        key = 'WARN'
    try:
        return LoggingSeverity[key]
    except KeyError:
        raise RuntimeError(f"'{log_severity}' is not a logging severity") from None


def get_logging_directory() -> Path:
    """Where ROS writes log files: $ROS_LOG_DIR, else $ROS_HOME/log, else ~/.ros/log."""
    log_dir = os.environ.get('ROS_LOG_DIR')
    if log_dir:
        return Path(os.path.expanduser(log_dir))
    ros_home = os.environ.get('ROS_HOME')
    if ros_home:
        return Path(os.path.expanduser(ros_home)) / 'log'
    home = os.environ.get('HOME') or os.environ.get('USERPROFILE') or os.path.expanduser('~')
    return Path(home) / '.ros' / 'log'


def _format(
    severity: int, name: str, message: str, stamp_ns: int, caller: inspect.Traceback
) -> str:
    fmt = os.environ.get('RCUTILS_CONSOLE_OUTPUT_FORMAT', DEFAULT_FORMAT)
    sec, nsec = divmod(stamp_ns, 1_000_000_000)
    fields = {
        'severity': _NAMES.get(severity, 'UNSET'),
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


# -- filters: each is (its parameters, the parameter that enables it) ------------------------
_FILTER_PARAMS = {
    'throttle': ('throttle_duration_sec', 'throttle_time_source_type'),
    'skip_first': ('skip_first',),
    'once': ('once',),
}
_REQUIRED = {'throttle': 'throttle_duration_sec', 'skip_first': 'skip_first', 'once': 'once'}
_RECOGNIZED = {p for params in _FILTER_PARAMS.values() for p in params} | {'name'}


def _filters(kwargs: Mapping[str, object]) -> list[str]:
    """The filters a call asks for (in the order they are applied); TypeError for arguments
    that belong to no filter, or a filter asked for without its required parameter."""
    for key in kwargs:
        if key not in _RECOGNIZED:
            raise TypeError(
                f"parameter '{key}' is not one of the recognized logging options "
                f'{sorted(_RECOGNIZED)}'
            )
    wanted = []
    for name, params in _FILTER_PARAMS.items():
        if any(p in kwargs for p in params):
            required = _REQUIRED[name]
            if required not in kwargs:
                raise TypeError(
                    f"required parameter '{required}' not specified but is required for the "
                    f"'{name}' filter"
                )
            # a false or zero enabling value leaves the filter out, as rclpy does
            if kwargs[required]:
                wanted.append(name)
    return wanted


class _CallSite:
    """The state of one logging call site of one logger."""

    __slots__ = ('filters', 'last_logged', 'logged', 'name', 'params', 'seen', 'severity')

    def __init__(
        self, name: str, severity: int, filters: list[str], params: dict[str, object]
    ) -> None:
        self.name = name
        self.severity = severity
        self.filters = filters
        self.params = params
        self.seen = False  # skip_first
        self.logged = False  # once
        self.last_logged = 0  # throttle, nanoseconds of its clock


class RcutilsLogger:
    """rclpy-compatible logger: debug/info/warn/error/fatal with once/skip_first/throttle."""

    def __init__(
        self,
        name: str = '',
        publish: Callable[[int, str, str, inspect.Traceback], None] | None = None,
    ) -> None:
        self.name = name
        self._publish = publish
        self._sites: dict[tuple[CodeType, int], _CallSite] = {}

    def get_child(self, name: str) -> RcutilsLogger:
        """The logger `<this name>.<name>` (it publishes to /rosout if this one does)."""
        if not name:
            raise ValueError('Child logger name must not be empty.')
        return RcutilsLogger(f'{self.name}.{name}' if self.name else name, self._publish)

    def set_level(self, level: int) -> None:
        """Set this logger's level (and its children's, unless they have their own)."""
        set_logger_level(self.name, level)

    def get_effective_level(self) -> LoggingSeverity:
        """The level that applies to this logger."""
        return get_logger_effective_level(self.name)

    def is_enabled_for(self, severity: int) -> bool:
        """Whether a message of `severity` would be logged."""
        return severity >= get_logger_effective_level(self.name)

    def log(self, message: object, severity: int, **kwargs: Unpack[LogOptions]) -> bool:
        """Log `message` at `severity` unless a filter or the level stops it; True if it
        was logged. Filters: `once`, `skip_first`, `throttle_duration_sec` (with
        `throttle_time_source_type`, a clock; system time by default); `name` logs under
        another logger name."""
        # the user's frame, found directly: inspect.stack() walked (and described) the whole
        # stack on every call, which made one log line cost 0.3-2 ms
        frame = sys._getframe(1)
        if frame.f_code in _LEVEL_METHODS and frame.f_back is not None:
            frame = frame.f_back  # called through debug()/info()/…
        name = kwargs.get('name', self.name)
        site = self._call_site(frame, name, severity, kwargs)
        if not severity >= get_logger_effective_level(name):
            return False
        if site.filters and not self._pass_filters(site, kwargs):
            return False
        code = frame.f_code
        caller = inspect.Traceback(code.co_filename, frame.f_lineno, code.co_name, None, None)
        text = str(message)
        if _console:
            line = _format(severity, name, text, time.time_ns(), caller)
            use_stdout = os.environ.get('RCUTILS_LOGGING_USE_STDOUT') == '1'
            if os.environ.get('RCUTILS_COLORIZED_OUTPUT') == '1' and _COLORS.get(severity):
                line = f'{_COLORS[severity]}{line}\033[0m'
            print(line, file=sys.stdout if use_stdout else sys.stderr, flush=True)
        if self._publish is not None:
            self._publish(severity, name, text, caller)
        return True

    def _call_site(
        self, frame: FrameType, name: str, severity: int, kwargs: Mapping[str, object]
    ) -> _CallSite:
        """The call site's state; its logger name, severity and filter arguments may not
        change between calls (as in rclpy)."""
        filters = _filters(kwargs) if kwargs else []
        params = {p: kwargs.get(p) for f in filters for p in _FILTER_PARAMS[f]}
        key = (frame.f_code, frame.f_lasti)
        site = self._sites.get(key)
        if site is None:
            site = self._sites[key] = _CallSite(name, severity, filters, params)
            return site
        if severity != site.severity:
            raise ValueError('Logger severity cannot be changed between calls.')
        if name != site.name:
            raise ValueError('Logger name cannot be changed between calls.')
        if filters != site.filters or params != site.params:
            raise ValueError('Logging filter parameters cannot be changed between calls.')
        return site

    @staticmethod
    def _pass_filters(site: _CallSite, kwargs: LogOptions) -> bool:
        """Apply the filters in order; the first that stops the call ends it."""
        for name in site.filters:
            if name == 'throttle':
                clock = kwargs.get('throttle_time_source_type')
                now = clock.now().nanoseconds if clock is not None else time.time_ns()
                period = cast(float, kwargs.get('throttle_duration_sec'))  # _filters required it
                if now - site.last_logged < period * 1e9:
                    return False
                site.last_logged = now
            elif name == 'skip_first':
                if not site.seen:
                    site.seen = True
                    return False
            elif name == 'once':
                if site.logged:
                    return False
                site.logged = True
        return True

    def debug(self, message: object, **kwargs: Unpack[LogOptions]) -> bool:
        """log() at DEBUG."""
        return self.log(message, DEBUG, **kwargs)

    def info(self, message: object, **kwargs: Unpack[LogOptions]) -> bool:
        """log() at INFO."""
        return self.log(message, INFO, **kwargs)

    def warning(self, message: object, **kwargs: Unpack[LogOptions]) -> bool:
        """log() at WARN (rclpy has both spellings)."""
        return self.log(message, WARN, **kwargs)

    def warn(self, message: object, **kwargs: Unpack[LogOptions]) -> bool:
        """log() at WARN."""
        return self.log(message, WARN, **kwargs)

    def error(self, message: object, **kwargs: Unpack[LogOptions]) -> bool:
        """log() at ERROR."""
        return self.log(message, ERROR, **kwargs)

    def fatal(self, message: object, **kwargs: Unpack[LogOptions]) -> bool:
        """log() at FATAL."""
        return self.log(message, FATAL, **kwargs)


_LEVEL_METHODS = {
    f.__code__
    for f in (
        RcutilsLogger.debug,
        RcutilsLogger.info,
        RcutilsLogger.warning,
        RcutilsLogger.warn,
        RcutilsLogger.error,
        RcutilsLogger.fatal,
    )
}

#: the logger all others descend from; its level is the default level
_root_logger = RcutilsLogger()


def get_logger(name: str) -> RcutilsLogger:
    """A console-only logger (no node, so nothing goes to /rosout)."""
    if not name:
        raise ValueError('Logger name must not be empty.')
    return _root_logger.get_child(name)
