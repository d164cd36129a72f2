"""The ROS side of the simulator: the gazebo node (server.py), message conversions and the
spawn_model client."""
