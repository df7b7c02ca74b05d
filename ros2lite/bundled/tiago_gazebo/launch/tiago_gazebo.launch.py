"""`tiago_gazebo.launch.py world_name:=<world>`: TIAGo on ros2lite's 2D simulator, as PAL's
launch file is included by br2_tiago's sim.launch.py. The arguments PAL's file takes for
the arm, end effector, public simulation and so on are accepted and change nothing here:
the 2D TIAGo is its base, laser, IMU and head camera. Velocity commands go through the
robot's twist multiplexer (key_vel, joy_vel, nav_vel, ...), as on the real robot. The top
view window opens with a display unless gui:=false or headless:=true."""

from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration

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


def generate_launch_description():
    from ros2lite.bundled.simulator import simulator_launch

    return simulator_launch(
        'tiago_gazebo',
        'tiago',
        [
            DeclareLaunchArgument('world_name', default_value='pal_office'),
            DeclareLaunchArgument('real_time_factor', default_value='1.0'),
            *(DeclareLaunchArgument(name, default_value='') for name in IGNORED),
        ],
        {
            'world': LaunchConfiguration('world_name'),
            'real_time_factor': LaunchConfiguration('real_time_factor'),
        },
    )
