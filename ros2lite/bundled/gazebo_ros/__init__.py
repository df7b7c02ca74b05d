"""gazebo_ros: Gazebo Classic's ROS entry points that courses call by name; here the spawner,
which adds a URDF robot to ros2lite's running 2D world."""
