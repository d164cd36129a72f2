"""A type-agnostic topic relay, drop-in for `rosrun topic_tools relay IN [OUT]`."""
