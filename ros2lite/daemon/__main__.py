"""The daemon process: ``python -m ros2lite.daemon --router ENDPOINT [--listen …] [--connect …]``.

Started by :func:`ros2lite.daemon.start`.  It forks once more so the router runs in its
own session, is re-parented to init (no zombie left with whoever started it) and reports
"pid N" / "ready" / "error MSG" through a pipe that this first process relays on stdout.
Nothing heavy (zenoh) is imported before the fork.  ``--foreground`` skips all that and runs
the router in this process, logging to stderr, for debugging.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
from pathlib import Path


def _parse(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="python -m ros2lite.daemon")
    parser.add_argument("--router", required=True, help="endpoint clients connect to")
    parser.add_argument("--listen", action="append", default=[], help="listen endpoint")
    parser.add_argument("--connect", action="append", default=[], help="router to mesh with")
    parser.add_argument("--pid-file", default=None)
    parser.add_argument("--log-file", default=None)
    parser.add_argument("--foreground", action="store_true")
    return parser.parse_args(argv)


def _detach(log_path: str | None) -> None:
    os.setsid()
    os.chdir("/")
    devnull = os.open(os.devnull, os.O_RDWR)
    if log_path:
        from ros2lite.util.files import open_for_writing

        out = open_for_writing(log_path, 0o600)  # never through a planted symlink
    else:
        out = devnull
    os.dup2(devnull, 0)
    os.dup2(out, 1)
    os.dup2(out, 2)


def _run(args: argparse.Namespace, ready_fd: int | None) -> int:

    from ros2lite.daemon.router import serve

    return serve(
        args.router,
        args.listen,
        args.connect,
        pid_path=Path(args.pid_file) if args.pid_file else None,
        log_path=Path(args.log_file) if args.log_file else None,
        ready_fd=ready_fd,
    )


def main(argv: list[str] | None = None) -> int:
    """`python -m ros2lite.daemon`: run the router (detached unless --foreground)."""
    args = _parse(argv)
    if args.foreground:
        return _run(args, None)
    read_fd, write_fd = os.pipe()
    child = os.fork()
    if child == 0:
        os.close(read_fd)
        code = 1
        try:
            _detach(args.log_file)
            code = _run(args, write_fd)
        except BaseException as exc:
            with contextlib.suppress(OSError):
                os.write(write_fd, f"error {exc}\n".encode())
        finally:
            os._exit(code)
    os.close(write_fd)
    with os.fdopen(read_fd) as pipe:
        handshake = pipe.read()
    sys.stdout.write(handshake)
    sys.stdout.flush()
    return 0 if "ready" in handshake.splitlines() else 1


if __name__ == "__main__":
    sys.exit(main())
