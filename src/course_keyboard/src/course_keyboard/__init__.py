"""The course's terminal keyboard: what every keyboard teleop needs, and nothing of ROS.

- terminal: RawTerminal puts a terminal in key-at-a-time mode (NotATerminal when stdin is none);
- decoder: KeyDecoder turns the bytes read into key names ('up', ..., or the character);
- arrows: the one table of the arrow keys' escape sequences (test keyboards type it, the decoder reads it);
- drive: what the arrows ask a robot to do (turtle_teleop_key's map: up forward, left turns left).

Exercises (turtlesim's turtle_teleop_key, mybot_teleop, lab2_turtlesim) and course_checks'
PtyKeyboard import it; it imports none of them.
"""
