"""The `ros2lite` command line: thin click wrappers over the library, one module per verb."""

from ros2lite.exceptions import quiet_interrupt_exit

# a Ctrl-C while the command line is still loading ends it quietly (main() catches later ones)
quiet_interrupt_exit()
