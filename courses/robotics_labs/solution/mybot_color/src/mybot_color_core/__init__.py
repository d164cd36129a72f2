"""Pen and background colours from the turtle's position (UPMC part 1, part B).

Named mybot_color_core so that scripts/mybot_color.py cannot shadow it on sys.path.
"""
