"""Keyboard teleoperation logic for mybot_teleop (UPMC part 1, parts A and C).

Named mybot_teleop_core, not mybot_teleop: the script scripts/mybot_teleop.py would
otherwise shadow the package when Python puts the script's folder first on sys.path.
"""
