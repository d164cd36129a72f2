"""TF2 with turtles: pose-to-frame geometry, the follow steering law, tf2_echo text."""
