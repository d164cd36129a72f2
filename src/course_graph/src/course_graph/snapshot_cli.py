"""graph_snapshot / rqt_graph: a picture of the running nodes and topics (rqt_graph for headless machines).

Queries the master (getSystemState), builds the graph (course_introspection.graph_model) and writes
PNG, SVG, PDF or DOT by the output's extension; prints the path. With a display and --show,
it also opens a window.
"""
from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path
from typing import List, Optional

from course_graph.dot import format_of, graph_to_dot, render
from course_introspection.graph_model import GraphOptions, SystemState, build_graph
from course_graph.viewer import can_show, show_png


def parse_args(argv: List[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="graph_snapshot", description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="rosgraph.png", help="file to write: .png .svg .pdf or .dot")
    view = parser.add_mutually_exclusive_group()
    view.add_argument("--nodes-only", action="store_true", help="node -> node edges labelled with topics")
    view.add_argument("--topics-only", action="store_true", help="topic -> topic edges through the nodes")
    parser.add_argument("--active", action="store_true", help="only topics with a publisher and a subscriber")
    parser.add_argument("--ns", action="append", default=[], metavar="NAMESPACE",
                        help="keep nodes and topics in this namespace (repeatable)")
    parser.add_argument("--show-debug", action="store_true", help="also draw /rosout and its topics")
    parser.add_argument("--show", action="store_true", help="open a window with the PNG when a display exists")
    return parser.parse_args(argv)


def main(argv: Optional[List[str]] = None) -> int:
    args = parse_args(sys.argv[1:] if argv is None else argv)
    import rosgraph  # only the command needs a master
    output = Path(args.output).resolve()
    try:
        format_of(output)
        options = GraphOptions(nodes_only=args.nodes_only, topics_only=args.topics_only, active_only=args.active,
                               namespaces=tuple(args.ns), hide_debug=not args.show_debug)
    except ValueError as err:
        print("graph_snapshot: %s" % err, file=sys.stderr)
        return 2
    master = rosgraph.Master("/graph_snapshot")
    try:
        state = SystemState.from_master(master.getSystemState())
    except Exception as err:  # socket errors, master errors: say where we looked
        print("graph_snapshot: cannot query the master at %s: %s" % (rosgraph.get_master_uri(), err), file=sys.stderr)
        return 1
    graph = build_graph(state, options)
    title = "ROS graph at %s" % rosgraph.get_master_uri()
    render(graph_to_dot(graph, title), output)
    print(output)
    if args.show and output.suffix == ".png" and can_show():
        show_png(str(output), title)
    return 0
