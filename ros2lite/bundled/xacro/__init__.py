"""xacro: the registry's own xacro (upstream's program, a bounded dependency) run as the ROS
package `xacro`, its `$(find pkg)` answered by ros2lite's package index."""
