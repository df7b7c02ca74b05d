"""`python -m ros2lite` runs the command line.

Ctrl-C must leave with status 2 here too, not by SIGINT: see
:func:`ros2lite.util.process.forget_caught_interrupt`.
"""

import sys

from ros2lite.cli.main import main
from ros2lite.util.process import forget_caught_interrupt

code = main()
forget_caught_interrupt()
sys.exit(code)
