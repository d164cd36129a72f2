"""The TF steps: `tf_frame` (a frame exists, with a parent) and `tf_follows` (a frame comes within
a distance of another), through one tf2 buffer and listener for the whole milestone."""
from __future__ import annotations

import math
import re
from typing import Dict, Optional

import rospy
import tf2_ros

from course_milestones.steps.state import StepState, failed
from course_checks.waiting import wait_for

# tf2's listing of the frames it knows: "Frame turtle1 exists with parent world."
_FRAME_LINE = re.compile(r"^Frame (\S+) exists with parent (\S+)\.$", re.MULTILINE)
LOOKUP_TIMEOUT_S = 0.2


class Frames:
    """A tf2 buffer filled by a listener from the milestone's first TF step on."""

    def __init__(self) -> None:
        self.buffer = tf2_ros.Buffer()
        self.listener = tf2_ros.TransformListener(self.buffer)

    def parents(self) -> Dict[str, str]:
        """Frame -> parent, of every frame seen so far."""
        return dict(_FRAME_LINE.findall(self.buffer.all_frames_as_string()))

    def distance(self, frame: str, target: str) -> Optional[float]:
        """How far `frame` is from `target` now (the latest transform), None when unknown."""
        try:
            seen = self.buffer.lookup_transform(target, frame, rospy.Time(0), rospy.Duration(LOOKUP_TIMEOUT_S))
        except tf2_ros.TransformException:
            return None
        move = seen.transform.translation
        return math.sqrt(move.x ** 2 + move.y ** 2 + move.z ** 2)


def frames_of(state: StepState) -> Frames:
    found = state.frames
    if found is None:
        found = state.frames = Frames()
        state.closers.append(found.listener.unregister)
    return found


def _strip(frame: str) -> str:
    return frame.lstrip("/")


def tf_frame(state: StepState, p: Dict, where: str) -> None:
    frames = frames_of(state)
    frame, parent = _strip(p["frame"]), _strip(p["parent"]) if p.get("parent") else None

    def present() -> bool:
        known = frames.parents()
        return frame in known and (parent is None or known[frame] == parent)
    if wait_for(present, float(p.get("within") or 0), 0.1):
        return
    known = frames.parents()
    if frame in known:
        raise failed("no_frame", "TF frame %s has the parent %s; the text's parent is %s" % (
            frame, known[frame], parent))
    listed = ", ".join("%s (parent %s)" % item for item in sorted(known.items())) or "none"
    raise failed("no_frame", "no TF frame %s on /tf or /tf_static within %g s (frames seen: %s)" % (
        frame, float(p.get("within") or 0), listed))


def tf_follows(state: StepState, p: Dict, where: str) -> None:
    frames = frames_of(state)
    frame, target, close = _strip(p["frame"]), _strip(p["target"]), float(p["distance"])
    seen = []

    def near() -> bool:
        now = frames.distance(frame, target)
        if now is not None:
            seen.append(now)
        return now is not None and now <= close
    if wait_for(near, float(p.get("within") or 0), 0.1):
        return
    if not seen:
        known = ", ".join(sorted(frames.parents())) or "none"
        raise failed("no_frame", "no transform between TF frames %s and %s (frames seen: %s)" % (frame, target, known))
    raise failed("check_failed", "TF frame %s came no closer than %.2f m to %s within %g s (last %.2f m); the text "
                 "asks it to come within %g m" % (frame, min(seen), target, float(p.get("within") or 0), seen[-1],
                                                  close))
