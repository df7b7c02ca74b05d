"""ros2lite's 2D world simulator: the courses' Gazebo robots as a flat world.

`world` holds the grid and its ray casts, `drive` the differential-drive base and its
odometry, `sensors` the laser, IMU and camera, `robots` the robots by the names they are
launched with, `worlds` the course worlds drawn as shapes, `node` the ROS node (the world,
its services and physics thread), `body` one robot's topics in it (`mux` its twist
multiplexer), and `spawn` how robots join.
"""
