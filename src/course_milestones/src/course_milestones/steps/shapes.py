"""What a turtle drew, judged from its poses (x, y, theta): the pure logic of the `draws`,
`in_bounds` and `pen_colour` steps, apart from ROS so that it is tested on generated paths.

A shape is judged on what a course text can ask of a student's drawing, whatever the node that
drove it: a circle by a least-squares fit of the positions and the heading turned (summed pose by
pose, course_milestones.turning, so laps past pi count); an arc by the angle turned and the fit's
radius; a square by the straight sides its path simplifies to (Ramer-Douglas-Peucker) and the
turns between them. Every judgement says what was drawn in a sentence a student can act on, and
none raises on a path too short or degenerate to judge: it says so instead.
"""
from __future__ import annotations

import math
from collections import Counter
from typing import List, NamedTuple, Optional, Sequence, Tuple

from course_milestones.turning import wrap

SHAPES = ("circle", "arc", "square")
Pose = Tuple[float, float, float]
Point = Tuple[float, float]
Rgb = Tuple[int, int, int]

MOVED_M = 0.05          # a turtle that went no farther (and turned less than MOVED_RAD) did not move
MOVED_RAD = 0.05
SAME_M = 1e-6           # positions closer than this are one place
STILL_POSES = 30        # this many identical last poses (about 0.5 s of turtlesim's 62.5 Hz): it stopped
SIDE_FRACTION = 0.25    # a straight piece shorter than this fraction of the square's size is a corner's
MERGE_RAD = math.pi / 4  # pieces meeting at a smaller turn are one side
MIN_TOLERANCE = 0.02    # the simplification's slack never goes below this fraction of the size


class Drawing(NamedTuple):
    """A judgement: whether the shape is there, whether the drawing is over (the shape complete,
    or past what the text asks), whether the turtle moved at all, and what was drawn in words."""

    holds: bool
    complete: bool
    moved: bool
    text: str


class Circle(NamedTuple):
    cx: float
    cy: float
    radius: float

    def off(self, point: Point) -> float:
        """How far `point` is from the circle (m)."""
        return abs(math.hypot(point[0] - self.cx, point[1] - self.cy) - self.radius)


class Side(NamedTuple):
    start: Point
    end: Point

    @property
    def length(self) -> float:
        return math.dist(self.start, self.end)

    @property
    def heading(self) -> float:
        return math.atan2(self.end[1] - self.start[1], self.end[0] - self.start[0])


# -- measures -----------------------------------------------------------------------------------------

def positions(poses: Sequence[Pose]) -> List[Point]:
    """The places visited, a place repeated (the turtle standing, or turning in place) once."""
    points: List[Point] = []
    for pose in poses:
        point = (float(pose[0]), float(pose[1]))
        if not points or math.dist(points[-1], point) > SAME_M:
            points.append(point)
    return points


def turned(poses: Sequence[Pose]) -> float:
    """The heading's change summed pose by pose (rad, left positive)."""
    return sum(wrap(b[2] - a[2]) for a, b in zip(poses, poses[1:]))


def path_length(points: Sequence[Point]) -> float:
    return sum(math.dist(a, b) for a, b in zip(points, points[1:]))


def moved(poses: Sequence[Pose]) -> bool:
    """Whether the turtle went anywhere or turned at all."""
    return path_length(positions(poses)) >= MOVED_M or abs(turned(poses)) >= MOVED_RAD


def still(poses: Sequence[Pose], count: int = STILL_POSES) -> bool:
    """Whether the turtle moved and then stood still for its last `count` poses."""
    if len(poses) <= count or not moved(poses):
        return False
    last = poses[-count:]
    return not moved(last) and all(math.dist(p[:2], last[0][:2]) <= SAME_M for p in last)


def fit_circle(points: Sequence[Point]) -> Optional[Circle]:
    """The least-squares circle through `points` (the algebraic fit, on coordinates centred on their
    mean for accuracy); None for fewer than three places or places on a line."""
    if len(points) < 3:
        return None
    n = float(len(points))
    mx, my = sum(p[0] for p in points) / n, sum(p[1] for p in points) / n
    us, vs = [p[0] - mx for p in points], [p[1] - my for p in points]
    suu, svv, suv = sum(u * u for u in us), sum(v * v for v in vs), sum(u * v for u, v in zip(us, vs))
    suuu = sum(u ** 3 for u in us) + sum(u * v * v for u, v in zip(us, vs))
    svvv = sum(v ** 3 for v in vs) + sum(u * u * v for u, v in zip(us, vs))
    det = suu * svv - suv * suv
    if det <= 1e-9 * (suu + svv) ** 2 or suu + svv <= 0.0:
        return None
    uc = 0.5 * (svv * suuu - suv * svvv) / det
    vc = 0.5 * (suu * svvv - suv * suuu) / det
    radius = math.sqrt(uc * uc + vc * vc + (suu + svv) / n)
    return Circle(uc + mx, vc + my, radius) if math.isfinite(radius) else None


def simplify(points: Sequence[Point], slack: float) -> List[Point]:
    """The path's corners: Ramer-Douglas-Peucker, keeping every place farther than `slack` from the
    line between the corners kept on either side of it (a stack, not recursion: long paths)."""
    if len(points) < 3:
        return list(points)
    keep = [False] * len(points)
    keep[0] = keep[-1] = True
    stack = [(0, len(points) - 1)]
    while stack:
        first, last = stack.pop()
        far, index = 0.0, -1
        for i in range(first + 1, last):
            away = _off_line(points[i], points[first], points[last])
            if away > far:
                far, index = away, i
        if index >= 0 and far > slack:
            keep[index] = True
            stack += [(first, index), (index, last)]
    return [p for p, kept in zip(points, keep) if kept]


def _off_line(point: Point, a: Point, b: Point) -> float:
    """How far `point` is from the segment a-b (from a, when a and b are one place)."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    span = dx * dx + dy * dy
    if span <= SAME_M * SAME_M:
        return math.dist(point, a)
    t = max(0.0, min(1.0, ((point[0] - a[0]) * dx + (point[1] - a[1]) * dy) / span))
    return math.dist(point, (a[0] + t * dx, a[1] + t * dy))


def sides(points: Sequence[Point], size: float, tolerance: float) -> List[Side]:
    """The straight sides of a path whose shape is about `size` across: its simplified pieces, those
    in line joined, then those shorter than a corner's dropped (and what they parted joined again)."""
    corners = simplify(points, max(tolerance, MIN_TOLERANCE) * size / 2.0)
    pieces = _joined([Side(a, b) for a, b in zip(corners, corners[1:]) if math.dist(a, b) > SAME_M])
    return _joined([piece for piece in pieces if piece.length >= SIDE_FRACTION * size])


def _joined(pieces: Sequence[Side]) -> List[Side]:
    """Pieces each joined to the one before when they meet at a turn below MERGE_RAD."""
    joined: List[Side] = []
    for piece in pieces:
        if joined and abs(wrap(piece.heading - joined[-1].heading)) < MERGE_RAD:
            joined[-1] = Side(joined[-1].start, piece.end)
        else:
            joined.append(piece)
    return joined


# -- the shapes ----------------------------------------------------------------------------------------

def circle(poses: Sequence[Pose], radius: Optional[float] = None, tolerance: float = 0.15) -> Drawing:
    """A full circle: the heading turned at least 2*pi*(1 - tolerance), every place within
    tolerance*radius of the fitted circle, whose radius is `radius` within tolerance (when given).
    Complete once it has turned so far: the circle drawn is then judged."""
    went, points, turn = moved(poses), positions(poses), abs(turned(poses))
    complete = turn >= 2 * math.pi * (1 - tolerance)
    if not complete:
        return Drawing(False, False, went, "it turned %.2f rad of the %.2f a circle needs" % (turn, 2 * math.pi))
    shape = _fitted(points, radius, tolerance, "circle")
    return shape._replace(complete=True, moved=went) if not shape.holds else Drawing(
        True, True, went, "it drew a circle (%s), turning %.2f rad" % (shape.text, turn))


def arc(poses: Sequence[Pose], angle: float, radius: Optional[float] = None, tolerance: float = 0.15,
        still_poses: int = STILL_POSES) -> Drawing:
    """An arc turning |angle| (within tolerance, either way) whose fitted radius is `radius` within
    tolerance (when given). Complete when the turtle stopped after moving, or turned past the
    angle's tolerance (it will not come back)."""
    went, turn, want = moved(poses), abs(turned(poses)), abs(angle)
    complete = still(poses, still_poses) or turn > want * (1 + tolerance)
    if abs(turn - want) > tolerance * want:
        return Drawing(False, complete, went, "it turned %.2f rad; the text asks an arc of %.2f rad" % (turn, want))
    shape = _fitted(positions(poses), radius, tolerance, "arc")
    text = "it drew an arc of %.2f rad (%s)" % (turn, shape.text) if shape.holds else shape.text
    return Drawing(shape.holds, complete, went, text)


def _fitted(points: Sequence[Point], radius: Optional[float], tolerance: float, what: str) -> Drawing:
    """The circle through `points`, judged: its radius against `radius`, the places' distance to it."""
    if path_length(points) < MOVED_M:
        return Drawing(False, False, False, "it turned in place: no %s drawn" % what)
    fit = fit_circle(points)
    if fit is None:
        return Drawing(False, False, True, "its path is a straight line, not a%s %s" % (
            "n" if what[0] in "aeiou" else "", what))
    if radius is not None and abs(fit.radius - radius) > tolerance * abs(radius):
        return Drawing(False, False, True, "it drew a%s %s of radius %.2f m; the text asks %g m" % (
            "n" if what[0] in "aeiou" else "", what, fit.radius, radius))
    worst = max(points, key=fit.off)
    if fit.off(worst) > tolerance * fit.radius:
        return Drawing(False, False, True, "its path strays %.2f m from the %s of radius %.2f m around (%.2f, %.2f) "
                                           "that fits it best, at (%.2f, %.2f): more than %.2f m" % (
                                               fit.off(worst), what, fit.radius, fit.cx, fit.cy, worst[0], worst[1],
                                               tolerance * fit.radius))
    return Drawing(True, False, True, "radius %.2f m around (%.2f, %.2f)" % (fit.radius, fit.cx, fit.cy))


def square(poses: Sequence[Pose], side: Optional[float] = None, tolerance: float = 0.15) -> Drawing:
    """Four straight sides of about `side` (when given; else of one length) joined by three turns of
    about pi/2 all the same way, the fourth side ending near where the first began. Complete once
    the fourth side closes the square or a fifth begins."""
    went, points = moved(poses), positions(poses)
    if len(points) < 2:
        return Drawing(False, False, went, "it drew no line (it %s)" % ("turned in place" if went else "stood still"))
    span = max(max(p[0] for p in points) - min(p[0] for p in points),
               max(p[1] for p in points) - min(p[1] for p in points))
    size = side if side else span
    if size <= MOVED_M:
        return Drawing(False, False, went, "its path is %.2f m across: no square drawn" % span)
    found = sides(points, size, tolerance)
    if len(found) < 4:
        return Drawing(False, False, went, "it drew %d straight side%s, not 4" % (len(found), "" if len(found) == 1
                                                                                  else "s"))
    four = found[:4]
    gap = math.dist(four[0].start, four[3].end)
    complete = len(found) > 4 or gap <= tolerance * size
    turns = [wrap(b.heading - a.heading) for a, b in zip(four, four[1:])]
    lengths = [s.length for s in four]
    mean = sum(lengths) / 4.0
    if any(abs(abs(t) - math.pi / 2) > tolerance * math.pi / 2 for t in turns) or \
            len({t > 0 for t in turns}) > 1:
        text = "its corners turn %s rad; a square's turn pi/2 (1.57) each, all the same way" % ", ".join(
            "%.2f" % t for t in turns)
    elif any(abs(length - (side or mean)) > tolerance * (side or mean) for length in lengths):
        text = "its sides are %s m long; the text asks %s" % (", ".join("%.2f" % x for x in lengths),
                                                             "%g m" % side if side else "four of one length")
    elif gap > tolerance * size:
        text = "its fourth side ends %.2f m from where the first began: the square is not closed" % gap
    else:
        return Drawing(True, True, went, "it drew a square of sides %s m, turning %s" % (
            ", ".join("%.2f" % x for x in lengths), "left" if turns[0] > 0 else "right"))
    return Drawing(False, complete, went, text)


def draws(poses: Sequence[Pose], shape: str, radius: Optional[float] = None, angle: Optional[float] = None,
          side: Optional[float] = None, tolerance: float = 0.15) -> Drawing:
    """The `draws` step's judgement of `shape` (one of SHAPES)."""
    if shape == "circle":
        return circle(poses, radius, tolerance)
    if shape == "arc":
        return arc(poses, angle or 0.0, radius, tolerance)
    if shape == "square":
        return square(poses, side, tolerance)
    return Drawing(False, True, moved(poses), "%r is not a shape (%s)" % (shape, ", ".join(SHAPES)))


# -- bounds and colours ----------------------------------------------------------------------------------

class Box(NamedTuple):
    """A rectangle of the canvas. Its edge is outside: turtlesim clamps a turtle that hits its wall
    onto the wall, so a pose on the canvas's edge is one that hit it."""

    xmin: float
    xmax: float
    ymin: float
    ymax: float

    def holds(self, pose: Pose) -> bool:
        return self.xmin < pose[0] < self.xmax and self.ymin < pose[1] < self.ymax


def first_outside(poses: Sequence[Pose], box: Box) -> Optional[int]:
    """The index of the first pose outside `box`, or None when every one is inside."""
    return next((i for i, pose in enumerate(poses) if not box.holds(pose)), None)


def colour_matches(seen: Rgb, wanted: Rgb, tolerance: int) -> bool:
    """Each channel within `tolerance` of the wanted one."""
    return all(abs(int(a) - int(b)) <= tolerance for a, b in zip(seen, wanted))


def colours_seen(colours: Sequence[Rgb], most: int = 3) -> str:
    """The colours sensed, most frequent first, with their share: '(179, 184, 255) 90%, ...'."""
    if not colours:
        return "no colour"
    counts = Counter(tuple(int(c) for c in colour) for colour in colours)
    shown = ["(%d, %d, %d)%s" % (rgb + (" %d%%" % round(100.0 * n / len(colours)) if len(counts) > 1 else "",))
             for rgb, n in counts.most_common(most)]
    return ", ".join(shown) + (" and %d other%s" % (len(counts) - most, "s" if len(counts) - most > 1 else "")
                               if len(counts) > most else "")
