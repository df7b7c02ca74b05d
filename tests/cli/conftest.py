"""Helpers to run the real CLI, in-process or as a subprocess."""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Callable
from dataclasses import dataclass

import pytest

from ros2lite.cli.main import main


@dataclass
class Result:
    code: int
    out: str
    err: str


@pytest.fixture
def run(capsys: pytest.CaptureFixture[str]) -> Callable[..., Result]:
    """Invoke `ros2lite ARGS…` in-process through the real entry point."""

    def invoke(*args: str) -> Result:
        code = main(list(args))
        captured = capsys.readouterr()
        return Result(code or 0, captured.out, captured.err)

    return invoke


def run_process(*args: str, stdin: str | None = None, env: dict[str, str] | None = None) -> Result:
    """Run `python -m ros2lite ARGS…` as a real process."""
    proc = subprocess.run(
        [sys.executable, '-m', 'ros2lite', *args],
        input=stdin,
        capture_output=True,
        text=True,
        timeout=60,
        env={**os.environ, **(env or {})},
    )
    return Result(proc.returncode, proc.stdout, proc.stderr)
