"""`python -m ros2lite.pkg.runner <module:function> <name> [argv…]`: run a Python
executable (a console script's target) the way its installed script would.

`sys.argv[0]` becomes the executable's name, the working directory is not importable (as for
an installed script), and the function's return value is the exit status. Being a module,
it also runs under a Python prefix: `ros2lite run --prefix 'python -m pdb' pkg exe`.
"""

from __future__ import annotations

import importlib
import os
import sys
from typing import Any

from ros2lite.exceptions import quiet_interrupt_exit
from ros2lite.util.process import forget_caught_interrupt, release_interrupts

USAGE = 'usage: python -m ros2lite.pkg.runner <module:function> <name> [argv...]'


def main() -> None:
    """Run the target named on the command line; exits with its status."""
    # a Ctrl-C the program does not catch (one in its start-up, before its `try`) ends it
    # by SIGINT as ever, without a traceback
    quiet_interrupt_exit()
    release_interrupts()  # `ros2lite run` held a Ctrl-C of our start-up until now
    if len(sys.argv) < 3 or ':' not in sys.argv[1]:
        print(USAGE, file=sys.stderr)
        raise SystemExit(2)
    target, name, *rest = sys.argv[1:]
    # `-m` put the working directory first; an installed script would not see it (a
    # PYTHONPATH entry naming the same directory, further on, stays)
    if sys.path and sys.path[0] in ('', '.', os.getcwd()):
        del sys.path[0]
    sys.argv[:] = [name, *rest]
    module, _, attr = target.partition(':')
    fn: Any = importlib.import_module(module)
    for part in attr.split('.'):
        fn = getattr(fn, part)
    try:
        code = fn()
    except SystemExit as e:
        code = e.code
    # a target that caught Ctrl-C leaves with its own status, as its installed script would
    forget_caught_interrupt()
    sys.exit(code)


if __name__ == '__main__':
    main()
