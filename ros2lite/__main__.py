"""`python -m ros2lite` runs the command line."""

from ros2lite.cli.main import run

run()
