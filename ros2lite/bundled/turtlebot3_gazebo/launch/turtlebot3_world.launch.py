"""`ros2lite launch turtlebot3_gazebo turtlebot3_world.launch.py`: TurtleBot3
($TURTLEBOT3_MODEL, burger by default) in the turtlebot3_world, on ros2lite's 2D simulator; the
description published by robot_state_publisher when that package is installed, by the
simulator otherwise; the top view window with a display unless gui:=false or
headless:=true."""


def generate_launch_description():
    from ros2lite.bundled.turtlebot3_gazebo.world_launch import world_launch

    return world_launch('turtlebot3_world')
