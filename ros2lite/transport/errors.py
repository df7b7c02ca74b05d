"""Errors of the Zenoh seam, under ros2lite's one base (importing this loads no zenoh)."""

from __future__ import annotations

import re

from ros2lite.exceptions import Ros2liteError

__all__ = [
    'ConfigError',
    'InsecureLinkError',
    'RouterUnavailableError',
    'SessionError',
    'zerror_message',
]


class ConfigError(Ros2liteError, ValueError):
    """A bad environment variable, config file or override; the message says which."""


class SessionError(Ros2liteError, RuntimeError):
    """A Zenoh session could not be opened (other than for a missing router)."""


class RouterUnavailableError(SessionError):
    """No Zenoh router answers at the endpoint a session was told to use."""

    def __init__(self, endpoint: str, detail: str = '') -> None:
        self.endpoint = endpoint
        self.detail = detail
        super().__init__(
            f"No Zenoh router answers at {endpoint} (start one with 'ros2lite daemon start')"
        )


def zerror_message(exc: BaseException) -> str:
    """A zenoh error as one readable line (without the trailing ' at /…/file.rs:NN.')."""
    text = re.sub(r"\s+at /\S+?\.rs:\d+\.?", "", str(exc).strip())
    m = re.search(r'msg: "(.*?)", location', text) or re.fullmatch(r'Str\("(.*)"\)', text)
    return (m.group(1) if m else text).rstrip(". ")


class InsecureLinkError(SessionError):
    """Security forbids a link that is not TLS, and the config names one."""
