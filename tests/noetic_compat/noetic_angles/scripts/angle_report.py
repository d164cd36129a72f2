#!/usr/bin/env python3
"""The C++ angle_report's twin: for each pair of angles (radians) on the command line, the first
normalised to [-pi, pi) and the shortest turn from the first to the second, from Python's angles."""
import sys

import angles


def main(argv):
    values = [float(a) for a in argv]
    for start, end in zip(values[0::2], values[1::2]):
        print("%.6f %.6f" % (angles.normalize_angle(start), angles.shortest_angular_distance(start, end)))


if __name__ == "__main__":
    main(sys.argv[1:])
