"""The `ros2lite` command line: thin click wrappers over the library, one module per verb."""
