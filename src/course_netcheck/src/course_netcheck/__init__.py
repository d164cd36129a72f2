"""ros_net_check: why ROS 1 traffic between machines silently fails (ROS_MASTER_URI, ROS_IP,
ROS_HOSTNAME). `diagnosis` is the pure logic; `cli` probes this host and the master."""
