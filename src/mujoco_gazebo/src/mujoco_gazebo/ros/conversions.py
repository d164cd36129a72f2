"""geometry_msgs <-> frames conversions (ROS quaternions are x, y, z, w; ours are w, x, y, z)."""
from __future__ import annotations

import rospy
from geometry_msgs.msg import Pose as PoseMsg, Twist as TwistMsg

from ..engine.frames import Pose, Twist
from ..engine.limits import pose_problem, twist_problem


def stamp_from_sim(seconds: float) -> rospy.Time:
    """Simulated time as a ROS stamp, rounded to the nearest nanosecond (negative -> 0).

    MuJoCo sums its step in floating point (1.0799999999999919 after 1080 steps of 1 ms) and
    rospy.Time.from_sec truncates, which would stamp half the /clock ticks 1 ns early
    (1.079999999); Gazebo's integer clock gives 1.080000000."""
    nsecs = max(0, int(round(seconds * 1e9)))
    return rospy.Time(nsecs // 1000000000, nsecs % 1000000000)


def pose_from_msg(msg: PoseMsg) -> Pose:
    p, q = msg.position, msg.orientation
    return Pose([p.x, p.y, p.z], [q.w, q.x, q.y, q.z])


def pose_to_msg(pose: Pose) -> PoseMsg:
    msg = PoseMsg()
    msg.position.x, msg.position.y, msg.position.z = (float(v) for v in pose.position)
    w, x, y, z = (float(v) for v in pose.orientation)
    msg.orientation.w, msg.orientation.x, msg.orientation.y, msg.orientation.z = w, x, y, z
    return msg


def twist_from_msg(msg: TwistMsg) -> Twist:
    return Twist([msg.linear.x, msg.linear.y, msg.linear.z], [msg.angular.x, msg.angular.y, msg.angular.z])


def twist_to_msg(twist: Twist) -> TwistMsg:
    msg = TwistMsg()
    msg.linear.x, msg.linear.y, msg.linear.z = (float(v) for v in twist.linear)
    msg.angular.x, msg.angular.y, msg.angular.z = (float(v) for v in twist.angular)
    return msg


def pose_msg_problem(msg: PoseMsg) -> str:
    """'' when the physics can hold this pose message, else why not (see limits.py)."""
    p, q = msg.position, msg.orientation
    return pose_problem((p.x, p.y, p.z), (q.x, q.y, q.z, q.w))


def twist_msg_problem(msg: TwistMsg) -> str:
    """'' when the physics can hold this twist message, else why not (see limits.py)."""
    return twist_problem((msg.linear.x, msg.linear.y, msg.linear.z), (msg.angular.x, msg.angular.y, msg.angular.z))
