#!/usr/bin/env python3
"""`make demo`: a private master on loopback, turtlesim, and a short scripted scene.

Three turtles draw with different pens (a red circle, a green spiral, a yellow
zig-zag); the canvas is saved as a PNG whose path is printed with a one-line
summary; everything started here is shut down before exit. Headless unless a
display is present, in which case the turtlesim window shows the scene.
"""
from __future__ import annotations

import math
import os
import shutil
import socket
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENE_SECONDS = 8.0


def free_port(preferred: int = 11311) -> int:
    for port in (preferred, 0):
        with socket.socket() as s:
            try:
                s.bind(("127.0.0.1", port))
                return s.getsockname()[1]
            except OSError:
                continue
    raise RuntimeError("no free port")


def wait_for_master(deadline: float) -> None:
    import rosgraph
    while not rosgraph.Master("/demo").is_online():
        if time.monotonic() > deadline:
            raise RuntimeError("the master did not come up")
        time.sleep(0.1)


def scene(out_dir: Path) -> str:
    import rospy
    from geometry_msgs.msg import Twist
    from std_srvs.srv import Trigger

    from turtlesim.msg import Pose
    from turtlesim.srv import SetPen, Spawn, TeleportAbsolute

    rospy.init_node("demo_scene")
    rospy.wait_for_service("/spawn", 30)
    spawn = rospy.ServiceProxy("/spawn", Spawn)
    spawn(2.0, 2.0, 0.0, "raphael")
    spawn(9.8, 1.2, 2.6, "michelangelo")
    for name in ("turtle1", "raphael", "michelangelo"):
        rospy.wait_for_service("/%s/set_pen" % name, 10)
    rospy.ServiceProxy("/turtle1/set_pen", SetPen)(0, 0, 0, 0, 1)  # lift the pen to move turtle1
    rospy.ServiceProxy("/turtle1/teleport_absolute", TeleportAbsolute)(5.5, 7.5, 0.0)
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline and abs(rospy.wait_for_message("/turtle1/pose", Pose, 5).y - 7.5) > 1e-3:
        pass
    pens = {"turtle1": (255, 40, 40, 4), "raphael": (40, 220, 90, 3), "michelangelo": (255, 215, 0, 5)}
    for name, (r, g, b, w) in pens.items():
        rospy.ServiceProxy("/%s/set_pen" % name, SetPen)(r, g, b, w, 0)
    pubs = {n: rospy.Publisher("/%s/cmd_vel" % n, Twist, queue_size=1) for n in pens}
    poses = []
    rospy.Subscriber("/turtle1/pose", Pose, lambda _m: poses.append(time.monotonic()))
    deadline = time.monotonic() + 10
    while any(p.get_num_connections() == 0 for p in pubs.values()) and time.monotonic() < deadline:
        time.sleep(0.01)

    rate = rospy.Rate(20)
    started = time.monotonic()
    while not rospy.is_shutdown() and (t := time.monotonic() - started) < SCENE_SECONDS:
        commands = {
            "turtle1": (2.0, 1.2),                                  # a circle
            "raphael": (0.4 + 0.35 * t, 2.5),                       # an opening spiral
            "michelangelo": (1.2, 2.5 if int(t / 0.8) % 2 else -2.5),  # a zig-zag
        }
        for name, (v, w) in commands.items():
            twist = Twist()
            twist.linear.x, twist.angular.z = v, w
            pubs[name].publish(twist)
        rate.sleep()
    window = [p for p in poses if p >= started + 1.0]
    pose_rate = (len(window) - 1) / (window[-1] - window[0]) if len(window) > 1 else 0.0
    answer = rospy.ServiceProxy("/turtlesim/snapshot", Trigger)()
    if not answer.success:
        raise RuntimeError(answer.message)
    target = out_dir / "turtlesim-demo.png"
    shutil.copyfile(answer.message, target)
    return "demo: 3 turtles drew for %.0f s; turtle1 pose rate %.1f Hz; canvas saved to %s" % (
        SCENE_SECONDS, pose_rate, target)


def main() -> int:
    out_dir = ROOT / "output"
    out_dir.mkdir(exist_ok=True)
    port = free_port()
    scratch = Path(tempfile.mkdtemp(prefix="turtle-demo-"))
    os.environ.update(ROS_MASTER_URI="http://localhost:%d" % port, ROS_HOSTNAME="localhost",
                      ROS_HOME=str(scratch), ROS_LOG_DIR=str(scratch / "log"))
    os.environ.pop("ROS_IP", None)
    from course_testkit.nodes import NodeProcess  # each in its own process group, stopped with it

    procs = []
    try:
        procs.append(NodeProcess(["roscore", "-p", str(port)], log_path=str(scratch / "roscore.log")))
        wait_for_master(time.monotonic() + 30)
        procs.append(NodeProcess(["rosrun", "turtlesim", "turtlesim_node",
                                  "_snapshot_dir:=%s" % (scratch / "snapshots")],
                                 log_path=str(scratch / "turtlesim.log")))
        summary = scene(out_dir)
    except Exception as err:  # report, then still clean up
        print("demo failed: %s (logs in %s)" % (err, scratch), file=sys.stderr)
        return 1
    finally:
        for proc in reversed(procs):
            proc.stop()
    print(summary)
    shutil.rmtree(scratch, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
