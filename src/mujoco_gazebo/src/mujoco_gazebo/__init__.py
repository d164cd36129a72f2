"""MuJoCo-backed simulator speaking Gazebo's ROS API: world logic, model formats, robot plugins."""
