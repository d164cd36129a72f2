"""What the physics can hold: the bounds every requested pose, twist and joint command must
respect before it reaches MuJoCo. A request outside them is refused with a reason (the
caller's success False / status_message, or a throttled warning on a topic), because MuJoCo
cannot integrate it: x = 1e30 trips its instability check, whose automatic reset used to put
every model back to its spawn pose and run /clock backwards.

The bounds (measured with a coke can and a TurtleBot3 Burger at the 1 ms step):
- positions: finite, every coordinate within +-WORLD_BOUND_M (10 km: far beyond any course
  world, and double precision still resolves 1e-8 m there);
- orientations: finite; a zero quaternion means "no rotation", as Gazebo's
  set_model_state and spawn services treat it (students' `rosservice call` leaves the
  orientation at 0 0 0 0); any other finite quaternion is normalised;
- twists: finite, |linear| <= MAX_LINEAR_SPEED and |angular| <= MAX_ANGULAR_SPEED
  (a can thrown at the ground at 30 m/s or spun at 100 rad/s already makes MuJoCo diverge);
- joint commands (position, velocity, effort): finite, |value| <= MAX_JOINT_COMMAND.
A state within the bounds that still diverges is caught by World.step, which restores the
last good state instead."""
from __future__ import annotations

import math
from typing import Iterable, Sequence

WORLD_BOUND_M = 1.0e4
MAX_LINEAR_SPEED = 20.0     # m/s
MAX_ANGULAR_SPEED = 20.0    # rad/s
MAX_JOINT_COMMAND = 1.0e4   # rad, m, rad/s, m/s, N m or N


def _finite(values: Iterable[float]) -> bool:
    return all(math.isfinite(float(v)) for v in values)


def _norm(values: Sequence[float]) -> float:
    """Euclidean norm without overflow for huge finite components (1e200 squared is inf)."""
    scale = max((abs(float(v)) for v in values), default=0.0)
    if scale == 0.0 or not math.isfinite(scale):
        return scale
    return scale * math.sqrt(sum((float(v) / scale) ** 2 for v in values))


def pose_problem(position: Sequence[float], orientation: Sequence[float]) -> str:
    """'' when the physics can hold this pose, else why not (position x y z, quaternion in any order)."""
    if not _finite(position):
        return "position %s is not finite" % _fmt(position)
    if max(abs(float(v)) for v in position) > WORLD_BOUND_M:
        return "position %s is outside the world (|x|, |y|, |z| <= %g m)" % (_fmt(position), WORLD_BOUND_M)
    if not _finite(orientation):
        return "orientation %s is not a finite quaternion" % _fmt(orientation)
    return ""


def twist_problem(linear: Sequence[float], angular: Sequence[float]) -> str:
    """'' when the physics can hold this twist, else why not."""
    if not _finite(linear) or not _finite(angular):
        return "twist %s %s is not finite" % (_fmt(linear), _fmt(angular))
    if _norm(linear) > MAX_LINEAR_SPEED:
        return "linear velocity %s is above %g m/s" % (_fmt(linear), MAX_LINEAR_SPEED)
    if _norm(angular) > MAX_ANGULAR_SPEED:
        return "angular velocity %s is above %g rad/s" % (_fmt(angular), MAX_ANGULAR_SPEED)
    return ""


def joint_command_problem(value: float) -> str:
    """'' for a joint command (position, velocity or effort) the physics can hold, else why not."""
    if not math.isfinite(value):
        return "command %r is not finite" % value
    if abs(value) > MAX_JOINT_COMMAND:
        return "command %g is beyond +-%g" % (value, MAX_JOINT_COMMAND)
    return ""


def _fmt(values: Sequence[float]) -> str:
    return "(%s)" % ", ".join("%g" % float(v) for v in values)
