"""joint_state_publisher: a joint state for every movable joint of a URDF robot, from other
sources where they give one, else from defaults (or sliders, in joint_state_publisher_gui)."""
