"""How the CLI turns failures into ros2cli-style exits without tracebacks."""

from __future__ import annotations

from ros2lite.exceptions import Ros2liteError


class CliError(Ros2liteError):
    """A user-facing failure: the message is printed alone on stderr, exit status 1."""

    def __init__(self, message: str, code: int = 1) -> None:
        super().__init__(message)
        self.code = code
