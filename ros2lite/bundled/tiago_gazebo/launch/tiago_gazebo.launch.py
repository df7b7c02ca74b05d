"""`tiago_gazebo.launch.py world_name:=<world>`: TIAGo on ros2lite's 2D simulator, as PAL's
launch file is included by br2_tiago's sim.launch.py. The arguments PAL's file takes for
the arm, end effector, public simulation and so on are accepted and change nothing here:
the 2D TIAGo is its base, laser, IMU and head camera. Velocity commands go through the
robot's twist multiplexer (key_vel, joy_vel, nav_vel, ...), as on the real robot. The top
view window opens with a display unless gui:=false or headless:=true."""

from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node

IGNORED = (
    'arm',
    'arm_type',
    'end_effector',
    'ft_sensor',
    'is_public_sim',
    'laser_model',
    'camera_model',
    'base_type',
    'navigation',
    'moveit',
    'slam',
    'gzclient',
    'tuck_arm',
)


def _robot_state_publisher():
    try:
        from ament_index_python.packages import get_package_share_directory

        get_package_share_directory('robot_state_publisher')
    except Exception:
        return None
    from ros2lite.sim.robots import robot, urdf

    return Node(
        package='robot_state_publisher',
        executable='robot_state_publisher',
        output='screen',
        parameters=[{'use_sim_time': True, 'robot_description': urdf(robot('tiago'))}],
    )


def generate_launch_description():
    state_publisher = _robot_state_publisher()
    simulator = Node(
        package='tiago_gazebo',
        executable='gazebo_2d',
        name='gazebo',
        output='screen',
        parameters=[
            {
                'world': LaunchConfiguration('world_name'),
                'real_time_factor': LaunchConfiguration('real_time_factor'),
                'publish_robot_state': state_publisher is None,
                'use_sim_time': True,
            }
        ],
    )
    actions = [
        DeclareLaunchArgument('world_name', default_value='pal_office'),
        DeclareLaunchArgument('real_time_factor', default_value='1.0'),
    ]
    actions += [DeclareLaunchArgument(name, default_value='') for name in IGNORED]
    actions.append(simulator)
    if state_publisher is not None:
        actions.append(state_publisher)
    from ros2lite.bundled.simulator import view_actions

    return LaunchDescription(actions + view_actions())
