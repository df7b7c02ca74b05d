"""robot_state_publisher: a URDF's joints as tf frames, fixed ones on `/tf_static`, moving
ones from `/joint_states` on `/tf`, and the description itself on `/robot_description`."""
