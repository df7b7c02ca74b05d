"""How the CLI turns failures into ros2cli-style exits without tracebacks."""

from __future__ import annotations


class CliError(Exception):
    """A user-facing failure: the message is printed alone on stderr, exit status 1."""

    def __init__(self, message: str, code: int = 1) -> None:
        super().__init__(message)
        self.code = code
