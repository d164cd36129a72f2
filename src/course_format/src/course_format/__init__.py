"""The course format, with no ROS: a course folder's course.yaml read and checked (course_file),
the primitives a data milestone's steps name (schema), a milestone (milestone) and the causes a
failure carries (causes). docs/course_format.md."""
