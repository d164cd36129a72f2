#!/usr/bin/env python3
"""`make demo`: a private master on loopback, turtlesim, and a short scripted scene.

Three turtles draw with different pens (a red circle, a green spiral, a yellow
zig-zag); the canvas is saved as a PNG whose path is printed with a one-line
summary; everything started here is shut down before exit. Headless unless a
display is present, in which case the turtlesim window shows the scene.

Every socket the demo listens on is bound to loopback (tests/test_demo_loopback.py checks
it with `ss`). rospy nodes and rosmaster bind to 127.0.0.1 when ROS_HOSTNAME=localhost, but
Debian's rosout, a roscpp node, always binds its XML-RPC server to 0.0.0.0 (xmlrpcpp binds
INADDR_ANY, whatever ROS_HOSTNAME or ROS_IP say). So the demo starts `rosmaster --core`
itself instead of `roscore` (= master + rosout): nodes still publish /rosout, nobody
aggregates it into /rosout_agg. The master's port is the kernel's pick, not 11311, so no
client left with the default ROS_MASTER_URI on this machine can reach into the demo
(course_testkit.master.PrivateMaster, the one private master of the workspace).
"""
from __future__ import annotations

import argparse
import shutil
import sys
import time
from pathlib import Path
from typing import Sequence

ROOT = Path(__file__).resolve().parents[1]
SCENE_SECONDS = 8.0


def scene(out_dir: Path, seconds: float = SCENE_SECONDS) -> str:
    """Spawn two turtles, give each a pen and a motion for `seconds`, save the canvas."""
    import rospy
    from geometry_msgs.msg import Twist
    from std_srvs.srv import Trigger

    from turtlesim.msg import Pose
    from turtlesim.srv import SetPen, Spawn, TeleportAbsolute

    from course_checks.waiting import wait_for

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
    wait_for(lambda: all(p.get_num_connections() for p in pubs.values()), timeout=10)

    rate = rospy.Rate(20)
    started = time.monotonic()
    while not rospy.is_shutdown() and (t := time.monotonic() - started) < seconds:
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
    return "demo: 3 turtles drew for %g s; turtle1 pose rate %.1f Hz; canvas saved to %s" % (
        seconds, pose_rate, target)


def parse_args(argv: Sequence[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seconds", type=float, default=SCENE_SECONDS, help="how long the turtles draw")
    parser.add_argument("--out", type=Path, default=ROOT / "output", help="where the canvas PNG goes")
    return parser.parse_args(argv)


def main(argv: Sequence[str]) -> int:
    args = parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    from course_testkit.master import PrivateMaster  # rosmaster --core alone: loopback only

    master = PrivateMaster()
    master.export()
    print("demo: private master at %s (loopback only)" % master.uri, flush=True)
    try:
        with master:
            master.start(["rosrun", "turtlesim", "turtlesim_node", "_snapshot_dir:=%s" % (master.home / "snapshots")],
                         "turtlesim")
            summary = scene(args.out, args.seconds)
    except Exception as err:  # report; the master has stopped everything and kept its logs
        print("demo failed: %s (logs in %s)" % (err, master.home), file=sys.stderr)
        return 1
    print(summary)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
