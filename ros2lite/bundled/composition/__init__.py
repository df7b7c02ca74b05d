"""The composition demo's components as Python classes (`composition::Talker`, `Listener`,
`Server`, `Client`), loadable into `ros2lite run rclpy_components component_container`.

Each takes a node's keyword arguments, as every component does (see
:mod:`ros2lite.components.registry`)."""
