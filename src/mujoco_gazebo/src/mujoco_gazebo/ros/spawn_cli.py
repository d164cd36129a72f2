"""`rosrun gazebo_ros spawn_model ...`: gazebo_ros's spawn_model arguments, parsed by a plain
function (unit-tested) and sent to /gazebo/spawn_{urdf,sdf}_model."""
from __future__ import annotations

import math
import sys
from dataclasses import dataclass, field
from typing import Dict, List, Optional

USAGE = """usage: spawn_model -urdf|-sdf (-file FILE | -param PARAM | -database NAME | -stdin) -model NAME
  [-x X] [-y Y] [-z Z] [-R ROLL] [-P PITCH] [-Y YAW] [-J JOINT ANGLE ...] [-reference_frame FRAME]
  [-robot_namespace NS] [-gazebo_namespace NS] [-unpause] [-wait MODEL] [-timeout SECONDS]"""


class UsageError(ValueError):
    pass


@dataclass
class SpawnArgs:
    fmt: str = ""                 # "urdf" | "sdf"
    source: str = ""              # "file" | "param" | "database" | "stdin"
    source_value: str = ""
    model: str = ""
    pose: List[float] = field(default_factory=lambda: [0.0] * 6)   # x y z R P Y
    joints: Dict[str, float] = field(default_factory=dict)
    reference_frame: str = ""
    robot_namespace: str = ""
    gazebo_namespace: str = "/gazebo"
    unpause: bool = False
    wait: str = ""
    timeout: float = 60.0


_POSE_FLAGS = {"-x": 0, "-y": 1, "-z": 2, "-R": 3, "-P": 4, "-Y": 5}


def parse_args(argv: List[str]) -> SpawnArgs:
    args = SpawnArgs()
    i = 0

    def value(flag: str) -> str:
        nonlocal i
        if i + 1 >= len(argv):
            raise UsageError("%s needs a value" % flag)
        i += 1
        return argv[i]

    while i < len(argv):
        a = argv[i]
        if a in ("-urdf", "-sdf", "-gazebo"):
            args.fmt = "urdf" if a == "-urdf" else "sdf"
        elif a in ("-file", "-param", "-database"):
            if args.source:
                raise UsageError("give only one of -file, -param, -database, -stdin")
            args.source, args.source_value = a[1:], value(a)
        elif a == "-stdin":
            args.source = "stdin"
        elif a == "-model":
            args.model = value(a)
        elif a in _POSE_FLAGS:
            text = value(a)
            try:
                number = float(text)
            except ValueError:
                raise UsageError("%s needs a number, got %r" % (a, text)) from None
            if not math.isfinite(number):
                raise UsageError("%s must be finite, got %r" % (a, text))
            args.pose[_POSE_FLAGS[a]] = number
        elif a == "-J":
            joint = value(a)
            args.joints[joint] = float(value(a))
        elif a == "-reference_frame":
            args.reference_frame = value(a)
        elif a == "-robot_namespace":
            args.robot_namespace = value(a)
        elif a == "-gazebo_namespace":
            args.gazebo_namespace = value(a)
        elif a == "-unpause":
            args.unpause = True
        elif a == "-wait":
            args.wait = value(a)
        elif a == "-timeout":
            args.timeout = float(value(a))
        elif a in ("-b", "-package_to_model"):
            pass  # accepted, no effect here
        else:
            raise UsageError("unknown argument %r" % a)
        i += 1
    if not args.model:
        raise UsageError("-model NAME is required")
    if not args.source:
        raise UsageError("one of -file, -param, -database, -stdin is required")
    if not args.fmt:
        args.fmt = "sdf" if args.source == "database" else ""
        if not args.fmt:
            raise UsageError("one of -urdf or -sdf is required")
    return args


def load_xml(args: SpawnArgs, get_param=None, stdin=None) -> str:
    """The model text from the chosen source (database models come from mujoco_gazebo.engine.database)."""
    if args.source == "file":
        try:
            with open(args.source_value) as f:
                return f.read()
        except OSError as exc:
            raise UsageError("cannot read %s: %s" % (args.source_value, exc)) from exc
    if args.source == "param":
        text = get_param(args.source_value) if get_param else None
        if not text:
            raise UsageError("parameter %s is not set or empty" % args.source_value)
        return str(text)
    if args.source == "database":
        from ..engine import database
        try:
            return database.model_sdf(args.source_value)
        except database.DatabaseError as exc:
            raise UsageError(str(exc)) from exc
    return (stdin or sys.stdin).read()


def main(argv: Optional[List[str]] = None) -> int:
    import rospy
    from course_rospy import quick_exit

    argv = rospy.myargv(sys.argv if argv is None else argv)[1:]
    quick_exit.install()  # rospy's exit without a spinning core
    rospy.init_node("spawn_model", anonymous=True)
    try:
        args = parse_args(argv)
        xml = load_xml(args, get_param=lambda p: rospy.get_param(p, None))
    except UsageError as exc:
        rospy.logfatal("spawn_model: %s\n%s" % (exc, USAGE))
        return 2
    if args.joints:
        rospy.logwarn("spawn_model: -J initial joint positions are ignored by this simulator")
    try:
        return _spawn(args, xml)
    except rospy.ROSInterruptException:  # Ctrl-C while waiting
        return 1
    except (rospy.ServiceException, rospy.ROSException, OSError) as exc:
        # gazebo died mid-call (transport error), or the master went away: gazebo_ros's message, no traceback
        rospy.logerr("Service call failed: %s" % exc)
        rospy.logfatal("spawn_model: gazebo is not running (or died during the call); model %s not spawned"
                       % args.model)
        return 1


def _spawn(args: SpawnArgs, xml: str) -> int:
    """Wait for gazebo's spawn service, call it, unpause if asked: 0 when the model is in."""
    import rospy
    from gazebo_msgs.srv import SpawnModel
    from geometry_msgs.msg import Pose as PoseMsg
    from std_srvs.srv import Empty

    from ..engine.frames import quat_from_rpy

    ns = args.gazebo_namespace.rstrip("/")
    service = "%s/spawn_%s_model" % (ns, args.fmt)
    rospy.loginfo("Waiting for service %s" % service)
    try:
        rospy.wait_for_service(service, timeout=args.timeout)
    except rospy.ROSException:
        rospy.logfatal("spawn_model: %s did not appear within %.0f s: gazebo is not running" % (service, args.timeout))
        return 1
    pose = PoseMsg()
    pose.position.x, pose.position.y, pose.position.z = args.pose[:3]
    w, x, y, z = quat_from_rpy(*args.pose[3:])
    pose.orientation.w, pose.orientation.x, pose.orientation.y, pose.orientation.z = w, x, y, z
    rospy.loginfo("Calling service %s" % service)
    resp = rospy.ServiceProxy(service, SpawnModel)(args.model, xml, args.robot_namespace, pose, args.reference_frame)
    rospy.loginfo("Spawn status: %s" % resp.status_message)
    if not resp.success:
        rospy.logerr("Spawn service failed. Exiting.")
        return 1
    if args.unpause:
        rospy.ServiceProxy("%s/unpause_physics" % ns, Empty)()
    return 0
