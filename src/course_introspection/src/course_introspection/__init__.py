"""Plain-data views of a running ROS system: the node graph and rqt_plot field paths."""
