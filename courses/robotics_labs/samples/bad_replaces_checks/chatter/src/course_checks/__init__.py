"""A student's own "checks library": same name as the course's, so it would replace it in the checks."""
