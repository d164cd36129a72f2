"""Pictures and diagnoses of a running ROS 1 system: node/topic graph, TF tree,
numeric topic fields over time (rqt_plot), network check."""
