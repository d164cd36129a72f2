"""The simulation engine: MuJoCo world, SDF/URDF reading, sensors and drive maths. No rospy
and no ROS message classes here (test_engine_without_ros checks it)."""
