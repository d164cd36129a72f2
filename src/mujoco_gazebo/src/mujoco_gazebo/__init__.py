"""MuJoCo-backed simulator speaking Gazebo's ROS API, in three layers:
engine/ (the world, model formats, sensors' maths: MuJoCo and numpy, no rospy),
plugins/ (one module per Gazebo robot plugin: the ROS face of a model) and
ros/ (the gazebo node's services and topics, the spawn_model client)."""
