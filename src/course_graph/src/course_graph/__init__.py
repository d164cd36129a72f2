"""Pictures and diagnoses of a running ROS 1 system: node/topic graph, TF tree, network check."""
