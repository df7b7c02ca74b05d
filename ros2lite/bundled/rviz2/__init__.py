"""ros2lite's rviz2: the live 3D scene (TF, scans, clouds, markers, maps, the robot) served
to any browser on viser; `--terminal` hands over to the top-down terminal view."""
