"""ros_gz_sim: the new Gazebo's ROS entry points that courses call by name; here `create`,
which adds a URDF robot to ros2lite's running 2D world."""
