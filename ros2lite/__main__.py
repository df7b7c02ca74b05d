"""`python -m ros2lite` runs the command line.

Ctrl-C must leave with status 2 here too. CPython's `-m` start-up, unlike a console script or
`-c`, ends the process by SIGINT (status -2, no message) when a Ctrl-C ever interrupted an
`exec()` of source text — dataclasses and namedtuples do that while modules load — even though
the CLI caught it. So status 2 leaves the way the other start-ups do: exit handlers, flushed
streams, then the exit itself, with nothing of CPython's left to look at that stale flag.
"""

import atexit
import contextlib
import os
import sys

from ros2lite.cli.main import main

code = main()
if code == 2:
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):
            stream.flush()
    os._exit(code)
sys.exit(code)
