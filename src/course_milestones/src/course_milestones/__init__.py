"""The check library: what a course's checks use to find what the texts leave open (executables,
message fields, key maps), start and watch the student's nodes, and judge them; the course file's
loader (course_file) and the causes of a failure (causes)."""
