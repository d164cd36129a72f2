"""Network address facts shared by the course's tools (no ROS in here)."""
