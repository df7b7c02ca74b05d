"""What tools stand on: a tool's door to the graph (connection), the checks of `doctor`, and
multicast probes. Above the library; the CLI and other tools import it."""
