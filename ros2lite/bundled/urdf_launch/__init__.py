"""urdf_launch: the launch files the URDF tutorial includes (Jazzy's urdf_tutorial shows its
robots through them): a package's xacro or URDF file to robot_state_publisher, and the joint
state publisher and viewer around it."""
