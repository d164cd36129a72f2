"""rqt_plot: plot numeric fields of ROS topics over time (a substitute for rqt_plot, which
Debian does not ship).

`rqt_plot /turtle1/pose/x /turtle1/pose/y` (or `/turtle1/pose/x:y`) opens a live window when a
display and a Qt/Tk matplotlib backend exist; headless, or with -o FILE, it records for
--seconds and writes a PNG (Ctrl-C stops early and still writes it). A topic that never
appears within --wait seconds, or a field that is not numeric, ends with exit 1 and a sentence.
"""
from __future__ import annotations

import argparse
import signal
import sys
import threading
import time
from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence

from course_graph.plot_buffer import SampleBuffer
from course_introspection.plot_fields import PlotField, PlotPathError, expand_shorthand, fields_of, parse_steps, \
    split_topic, value_of

PROG = "rqt_plot"
DEFAULT_OUTPUT = "plot.png"
POLL_S = 0.1


class PlotError(RuntimeError):
    """Ends the node with exit 1 and this one-line message."""


def parse_args(argv: Sequence[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog=PROG, description=__doc__.splitlines()[0])
    parser.add_argument("topics", nargs="+", metavar="TOPIC/FIELD",
                        help="e.g. /turtle1/pose/x, /turtle1/pose/x:y, /joint_states/position[0]")
    parser.add_argument("-o", "--output", help="write a PNG here instead of opening a window "
                                               "(default without a display: %s)" % DEFAULT_OUTPUT)
    parser.add_argument("--seconds", type=float, default=10.0, help="how long to record for the PNG (default 10)")
    parser.add_argument("--wait", type=float, default=5.0, help="how long to wait for the topics to appear "
                                                                "(default 5 s)")
    parser.add_argument("--span", type=float, default=20.0, help="seconds shown by the live window (default 20)")
    args = parser.parse_args(list(argv))
    if args.seconds <= 0 or args.wait < 0 or args.span <= 0:
        parser.error("--seconds and --span must be > 0, --wait >= 0")
    return args


def requested_paths(arguments: Sequence[str]) -> List[str]:
    """The arguments as full paths (shorthands expanded, relative names resolved like rqt_plot)."""
    import rosgraph.names
    paths = [rosgraph.names.script_resolve_name(PROG, p) for p in expand_shorthand(arguments)]
    for path in paths:
        parse_steps(path)  # a syntax error is reported before any waiting
    return paths


def advertised_topics() -> Dict[str, str]:
    """Topic -> type of every topic some node publishes."""
    import rosgraph
    try:
        return dict(rosgraph.Master("/" + PROG).getPublishedTopics("/"))
    except Exception as err:  # socket errors and master failures alike
        raise PlotError("cannot reach the ROS master at %s (is roscore running?): %s"
                        % (rosgraph.get_master_uri(), err)) from err


def wait_for_topics(paths: Sequence[str], wait_s: float) -> Dict[str, str]:
    """The advertised topics once every path starts with one, or after wait_s; then a path that
    still has no topic is an error."""
    deadline = time.monotonic() + wait_s
    while True:
        topics = advertised_topics()
        missing = [p for p in paths if split_topic(p, topics) is None]
        if not missing:
            return topics
        if time.monotonic() >= deadline:
            raise PlotError("topic %s does not exist (nothing publishes it after %g s)" % (missing[0], wait_s))
        time.sleep(POLL_S)


def subscribe(by_topic: Dict[str, List[PlotField]], topics: Dict[str, str], buffer: SampleBuffer,
              clock: Callable[[Any], float]) -> list:
    """A subscriber per topic that adds each field's number to the buffer."""
    import rospy
    from course_introspection.plot_fields import message_class

    def on_message(message: Any, fields: List[PlotField]) -> None:
        stamp = clock(message)
        for field in fields:
            value = value_of(message, field.steps)
            if value is not None:
                buffer.add(field.label, stamp, value)

    return [rospy.Subscriber(topic, message_class(topics[topic]), on_message, callback_args=fields)
            for topic, fields in by_topic.items()]


def message_clock(start: float) -> Callable[[Any], float]:
    """Seconds since `start` of a message: its header stamp when it has a non-zero one (as
    rqt_plot does), else the time it arrived."""
    import rospy

    def seconds(message: Any) -> float:
        stamp = getattr(getattr(message, "header", None), "stamp", None)
        if stamp is not None and hasattr(stamp, "to_sec") and not stamp.is_zero():
            return stamp.to_sec() - start
        return rospy.get_time() - start
    return seconds


def output_path(output: Optional[str]) -> Path:
    """Where the picture goes; its folder must exist before anything is recorded."""
    from course_graph.plot_figure import check_format
    path = Path(output or DEFAULT_OUTPUT).resolve()
    if not path.parent.is_dir():
        raise PlotError("cannot write %s: no folder %s" % (path, path.parent))
    try:
        check_format(path)
    except ValueError as err:
        raise PlotError("cannot write %s: %s" % (path, err)) from err
    return path


def record_png(buffer: SampleBuffer, output: Path, seconds: float, stop: threading.Event, title: str) -> None:
    """Record until `seconds` have passed or `stop` is set (Ctrl-C), then write the picture."""
    from course_graph.plot_figure import save_figure
    deadline = time.monotonic() + seconds
    while not stop.is_set() and time.monotonic() < deadline:
        stop.wait(min(POLL_S, max(0.0, deadline - time.monotonic())))
    try:
        save_figure(buffer.snapshot(), output, title)
    except (OSError, ValueError) as err:
        raise PlotError("cannot write %s: %s" % (output, err)) from err
    print(output)
    silent = buffer.empty_labels()
    if silent:
        print("%s: no message for %s (the picture has no line for it)" % (PROG, ", ".join(silent)), file=sys.stderr)


def main(argv: Optional[List[str]] = None) -> int:
    import rospy
    args = parse_args(rospy.myargv(sys.argv)[1:] if argv is None else argv)
    try:
        return plot(args)
    except (PlotError, PlotPathError) as err:
        print("%s: %s" % (PROG, err), file=sys.stderr)
        return 1
    except ImportError as err:  # matplotlib (or its numpy) missing
        print("%s: %s (Debian's python3-matplotlib is needed: make deps)" % (PROG, err), file=sys.stderr)
        return 1
    except KeyboardInterrupt:  # Ctrl-C while waiting for the topics: nothing recorded yet
        return 130


def plot(args: argparse.Namespace) -> int:
    """Find the fields, subscribe, then show the live window or record and write the picture."""
    import rospy
    from course_graph.plot_live import gui_backend
    paths = requested_paths(args.topics)
    output = output_path(args.output) if args.output else None
    topics = wait_for_topics(paths, args.wait)
    by_topic = fields_of(paths, topics)
    backend = None if output else gui_backend()
    if not backend and not output:
        output = output_path(None)
        print("%s: no window (no display, or no Qt/Tk for matplotlib): recording %g s into %s (Ctrl-C stops "
              "early)" % (PROG, args.seconds, output), file=sys.stderr)
    labels = [field.label for fields in by_topic.values() for field in fields]
    buffer = SampleBuffer(labels, keep_seconds=args.span if backend else None)
    stop = threading.Event()
    signal.signal(signal.SIGINT, lambda *_: stop.set())
    signal.signal(signal.SIGTERM, lambda *_: stop.set())
    rospy.init_node(PROG, anonymous=True, disable_signals=True)
    start = rospy.get_time()
    subscribe(by_topic, topics, buffer, message_clock(start))
    title = " ".join(args.topics)
    try:
        if backend:
            from course_graph.plot_live import run_window
            run_window(buffer, lambda: rospy.get_time() - start, args.span, title, stop)
        else:
            record_png(buffer, output, args.seconds, stop, title)
    finally:
        rospy.signal_shutdown("done")
    return 0
