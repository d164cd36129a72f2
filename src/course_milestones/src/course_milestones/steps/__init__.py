"""A milestone written as data: named, parameterised steps (course_format.schema) that the
generic check node `course_check` runs in order against the student's processes."""
