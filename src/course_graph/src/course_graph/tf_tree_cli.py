"""tf_tree: a picture of the TF tree (rqt_tf_tree / view_frames for headless machines).

Listens to /tf and /tf_static for --wait seconds (or until every --frame is known, at most
--timeout s), then writes the tree from tf2's all_frames_as_yaml() as PNG/SVG/PDF/DOT and
prints the path and an indented text tree.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import List, Optional

from course_graph.dot import format_of, render, tree_to_dot
from course_graph.tf_tree_model import frames_of, parse_frames_yaml, tree_edges, tree_text
from course_graph.viewer import can_show, show_png


def parse_args(argv: List[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="tf_tree", description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="tf_tree.png", help="file to write: .png .svg .pdf or .dot")
    parser.add_argument("--wait", type=float, default=2.0, help="seconds to listen (default 2)")
    parser.add_argument("--frame", action="append", default=[], help="wait until this frame is known (repeatable)")
    parser.add_argument("--timeout", type=float, default=20.0, help="longest wait for --frame (s)")
    parser.add_argument("--show", action="store_true", help="open a window with the PNG when a display exists")
    return parser.parse_args(argv)


def main(argv: Optional[List[str]] = None) -> int:
    import rospy
    args = parse_args(rospy.myargv(sys.argv)[1:] if argv is None else argv)
    output = Path(args.output).resolve()
    try:
        format_of(output)
    except ValueError as err:
        print("tf_tree: %s" % err, file=sys.stderr)
        return 2
    import tf2_ros
    rospy.init_node("tf_tree", anonymous=True)
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer)
    wanted = set(args.frame)
    start = rospy.get_time()
    limit = args.timeout if wanted else args.wait
    while not rospy.is_shutdown() and rospy.get_time() - start < limit:
        if wanted and wanted <= frames_of(parse_frames_yaml(buffer.all_frames_as_yaml())):
            break
        rospy.sleep(0.1)
    links = parse_frames_yaml(buffer.all_frames_as_yaml())
    missing = wanted - frames_of(links)
    render(tree_to_dot(tree_edges(links), frames_of(links), "TF tree"), output)
    print(output)
    print(tree_text(links), end="")
    if missing:
        print("tf_tree: never saw the frame(s) %s" % ", ".join(sorted(missing)), file=sys.stderr)
        return 1
    if args.show and output.suffix == ".png" and can_show():
        show_png(str(output), "TF tree")
    return 0
