"""The check library: what a course's checks use to find what the texts leave open (executables,
launch files, message types), start and watch the student's nodes, believe only the world's
simulators (the trust guard), and judge them (MilestoneCase, the step primitives of a data
milestone). The course format it checks against (the course file, the steps' schema, the causes)
is course_format's, which imports no ROS."""
