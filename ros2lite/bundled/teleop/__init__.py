"""What the keyboard teleop demos share: a node spinning on a thread of its own while the main
thread reads keys (`ros2lite.util.keyboard`), and the loop that does both."""
