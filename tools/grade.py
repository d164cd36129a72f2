#!/usr/bin/env python3
"""The milestone grader: runs every milestone rostest and prints milestone, text/section,
pass/fail and time; exits non-zero if any fails.

Run from a sourced workspace (`make grade`). Each rostest starts its own master on a free
port. To grade a student's node, run one rostest by hand with its args, e.g.
    rostest mybot_color milestone_color.test node_pkg:=student_pkg node_type:=color.py
or pass --only NAME and extra args: python3 tools/grade.py --only color node_pkg:=student_pkg

The verdict is read from rostest's SUMMARY (`* RESULT: SUCCESS`): `rostest --text` exits 0
even when a test fails, so its exit code alone says nothing.
"""
from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time
from typing import List, NamedTuple, Sequence


class Milestone(NamedTuple):
    name: str
    text: str
    package: str
    test_file: str
    args: Sequence[str] = ()


# The one list of milestones (seed text and section -> rostest).
MILESTONES: List[Milestone] = [
    Milestone("teleop", "001 UPMC part 1, 2.1 (Part A teleop)", "mybot_teleop", "milestone_teleop.test"),
    Milestone("color", "001 UPMC part 1, 2.2 (Part B services)", "mybot_color", "milestone_color.test"),
    Milestone("launch_params", "001 UPMC part 1, 2.3 (Part C launch/params)", "mybot_teleop", "milestone_launch.test"),
    Milestone("turtlebot", "001 UPMC part 1, 2.3.3 (TurtleBot3 Burger teleop)", "mybot_teleop",
              "milestone_turtlebot.test"),
    Milestone("chatter", "002 Lab 2, section 2 (example pub/sub)", "chatter", "milestone_chatter.test"),
    Milestone("checkpoint1", "002 Lab 2, checkpoint 1 (TimestampString)", "my_chatter", "milestone_my_chatter.test"),
    Milestone("checkpoint2", "002 Lab 2, checkpoint 2 (turtle controller)", "lab2_turtlesim",
              "milestone_turtle_controller.test"),
    Milestone("checkpoint3", "002 Lab 2, checkpoint 3 (patrol service)", "turtle_patrol", "milestone_patrol.test"),
    Milestone("arch", "003 Ex. 1, Writing our first node (Tasks 1-8)", "my_pkg", "milestone_arch.test"),
    Milestone("two_turtles", "003 Ex. 1, Launch Files task", "two_turtles", "milestone_two_turtles.test"),
    Milestone("two_turtles_topic_tools", "003 Ex. 1, Launch Files (Debian topic_tools relay)", "two_turtles",
              "milestone_two_turtles.test", ("relay_pkg:=topic_tools",)),
    Milestone("backgrounds", "003 Ex. 1, ROS Parameters task", "two_turtles", "milestone_backgrounds.test"),
    Milestone("relay", "003 relay: drop-in topic_tools relay (ours)", "course_relay", "relay_behaviour.test"),
    Milestone("relay_topic_tools", "003 relay: same test, Debian topic_tools", "course_relay",
              "relay_behaviour.test", ("relay_pkg:=topic_tools",)),
    Milestone("pose_subscriber", "000 pose subscriber (ROS 1 form)", "my_robot_controller",
              "milestone_pose_subscriber.test"),
    Milestone("interfaces", "004 custom interfaces (msg/srv/action)", "pkg_interfaces", "milestone_interfaces.test"),
    Milestone("param", "004 parameters (robot_name, dump/load)", "pkg_param", "milestone_param.test"),
    Milestone("graph_picture", "003 Ex. 1 Part I task 3 (rqt_graph picture)", "course_graph",
              "graph_two_turtles.test"),
    Milestone("gazebo_rrbot", "003 Ex. 1 Part II tasks 1-3 (RRBot, coke can)", "mujoco_gazebo", "rrbot_world.test"),
    Milestone("tf2_follow", "004 10 TF2 (broadcaster, follower)", "turtle_tf2", "follow.test"),
    Milestone("tf2_static", "004 10.4 static transform A->B", "turtle_tf2", "static_transform.test"),
]

TIMEOUT_S = 300


def run(m: Milestone, extra: Sequence[str], keep_logs: str) -> tuple:
    env = dict(os.environ, ROS_HOSTNAME="localhost", QT_QPA_PLATFORM="offscreen",
               ROS_HOME=os.path.join(keep_logs, m.name), ROS_LOG_DIR=os.path.join(keep_logs, m.name, "log"))
    env.pop("DISPLAY", None)
    env.pop("ROS_MASTER_URI", None)
    started = time.monotonic()
    try:
        proc = subprocess.run(["rostest", "--text", m.package, m.test_file] + list(m.args) + list(extra),
                              env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                              timeout=TIMEOUT_S)
        output = proc.stdout
    except subprocess.TimeoutExpired as err:
        output = (err.stdout or b"").decode(errors="replace") if isinstance(err.stdout, bytes) else (err.stdout or "")
        output += "\n(timed out)"
    elapsed = time.monotonic() - started
    results = re.findall(r"\* RESULT: (\w+)", output)
    passed = bool(results) and all(r == "SUCCESS" for r in results)
    with open(os.path.join(keep_logs, m.name + ".log"), "w") as f:
        f.write(output)
    return passed, elapsed


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--only", action="append", help="run only these milestones (by name)")
    parser.add_argument("--list", action="store_true", help="list the milestones and exit")
    parser.add_argument("extra", nargs="*", help="extra rostest args (name:=value) for the selected milestones")
    opts = parser.parse_args(argv)
    selected = [m for m in MILESTONES if not opts.only or m.name in opts.only]
    if opts.list or not selected:
        for m in MILESTONES:
            print("%-26s %-50s rostest %s %s %s" % (m.name, m.text, m.package, m.test_file, " ".join(m.args)))
        return 0 if opts.list else 2
    logs = tempfile.mkdtemp(prefix="grade-")
    rows, failed = [], 0
    print("%-26s %-52s %-6s %8s" % ("milestone", "text / section", "result", "time"))
    print("-" * 96)
    for m in selected:
        passed, elapsed = run(m, opts.extra, logs)
        failed += not passed
        print("%-26s %-52s %-6s %7.1fs" % (m.name, m.text, "pass" if passed else "FAIL", elapsed), flush=True)
    print("-" * 96)
    print("%d of %d milestones pass; logs in %s" % (len(selected) - failed, len(selected), logs))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
