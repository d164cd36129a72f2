"""A milestone written as data: named, parameterised steps (course_format.schema) that the
generic check node `run_steps` runs in order against the student's processes."""
