"""A student's own "testkit": same name as the course's, so it would replace it in the checks."""
