"""ros2lite's take on ROS's action_tutorials_py: a Fibonacci action server and client on
`fibonacci` (action_tutorials_interfaces/action/Fibonacci)."""
