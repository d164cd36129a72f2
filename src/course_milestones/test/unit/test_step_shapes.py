"""steps.shapes: generated circles, arcs and squares (any centre, size, start heading, direction
and a little sampling noise) are recognised with their parameters; near misses are not, and say
what was drawn; no input, however degenerate, makes a judgement raise."""
import math
import random

import pytest
from hypothesis import given, settings, strategies as st

from course_milestones.steps import shapes
from course_milestones.steps.shapes import Box
from course_milestones.turning import wrap

CENTRES = st.floats(-20.0, 20.0)
HEADINGS = st.floats(-math.pi, math.pi)
DIRECTIONS = st.sampled_from((1.0, -1.0))
NOISE = st.floats(0.0, 0.005)   # a fraction of the shape's size
SEEDS = st.integers(0, 2 ** 32 - 1)


def noisy(points, amount, seed):
    """Each pose moved by up to `amount` on both axes."""
    rng = random.Random(seed)
    return [(x + rng.uniform(-amount, amount), y + rng.uniform(-amount, amount), th) for x, y, th in points]


def circling(cx, cy, radius, start, direction, turn, samples):
    """Poses along a circle: from the place at angle `start` around (cx, cy), turning `turn` rad
    (left when direction is 1), heading along the circle."""
    poses = []
    for i in range(samples + 1):
        phi = start + direction * turn * i / samples
        heading = phi + direction * math.pi / 2
        poses.append((cx + radius * math.cos(phi), cy + radius * math.sin(phi), wrap(heading)))
    return poses


def squaring(x, y, heading, side, direction, step, laps=1.0, turn_step=0.1):
    """Poses of a turtle driving a square: a side in steps of `step` m, a quarter turn in place in
    steps of `turn_step` rad, four times (times `laps`)."""
    poses = [(x, y, heading)]
    for _ in range(int(round(4 * laps))):
        n = max(1, int(round(side / step)))
        x0, y0 = x, y
        for i in range(1, n + 1):
            x, y = x0 + side * i / n * math.cos(heading), y0 + side * i / n * math.sin(heading)
            poses.append((x, y, wrap(heading)))
        goal = heading + direction * math.pi / 2
        while abs(goal - heading) > 1e-9:
            heading += direction * min(turn_step, abs(goal - heading))
            poses.append((x, y, wrap(heading)))
    return poses


@settings(max_examples=60, deadline=None)
@given(CENTRES, CENTRES, st.floats(0.3, 5.0), HEADINGS, DIRECTIONS, st.floats(1.0, 1.6), st.integers(60, 400),
       NOISE, SEEDS)
def test_a_circle_is_recognised_with_its_radius(cx, cy, radius, start, direction, laps, samples, noise, seed):
    poses = noisy(circling(cx, cy, radius, start, direction, laps * 2 * math.pi, samples), noise * radius, seed)
    judged = shapes.circle(poses, radius)
    assert judged.holds and judged.complete and judged.moved, judged.text
    fit = shapes.fit_circle(shapes.positions(poses))
    assert abs(fit.radius - radius) < 0.02 * radius and math.hypot(fit.cx - cx, fit.cy - cy) < 0.02 * radius


@settings(max_examples=40, deadline=None)
@given(CENTRES, CENTRES, st.floats(0.3, 5.0), HEADINGS, DIRECTIONS, st.integers(60, 300), NOISE, SEEDS)
def test_seventy_percent_of_a_circle_is_not_one(cx, cy, radius, start, direction, samples, noise, seed):
    poses = noisy(circling(cx, cy, radius, start, direction, 0.7 * 2 * math.pi, samples), noise * radius, seed)
    judged = shapes.circle(poses, radius)
    assert not judged.holds and not judged.complete
    assert "of the 6.28 a circle needs" in judged.text


def test_a_circle_of_another_radius_says_both():
    judged = shapes.circle(circling(5, 5, 2.0, 0, 1, 7.0, 400), radius=1.0)
    assert not judged.holds and judged.complete
    assert "radius 2.00 m; the text asks 1 m" in judged.text


def test_a_square_is_not_a_circle():
    judged = shapes.circle(squaring(2, 2, 0, 2.0, 1, 0.05, laps=2))
    assert not judged.holds and judged.complete and "strays" in judged.text


@settings(max_examples=60, deadline=None)
@given(CENTRES, CENTRES, st.floats(0.3, 5.0), HEADINGS, DIRECTIONS, st.floats(0.6, 5.5), st.integers(40, 300),
       NOISE, SEEDS)
def test_an_arc_is_recognised_with_its_angle_and_radius(cx, cy, radius, start, direction, angle, samples, noise,
                                                        seed):
    poses = noisy(circling(cx, cy, radius, start, direction, angle, samples), noise * radius, seed)
    poses += [poses[-1]] * (shapes.STILL_POSES + 1)
    judged = shapes.arc(poses, angle, radius)
    assert judged.holds and judged.complete, judged.text
    assert "it drew an arc of %.2f rad" % angle in judged.text


def test_an_arc_turned_too_far_or_not_far_enough():
    short = shapes.arc(circling(5, 5, 1.0, 0, 1, 1.0, 100), math.pi)
    assert not short.holds and not short.complete and "turned 1.00 rad; the text asks an arc of 3.14" in short.text
    far = shapes.arc(circling(5, 5, 1.0, 0, -1, 4.0, 100), math.pi)
    assert not far.holds and far.complete
    wide = shapes.arc(circling(5, 5, 1.0, 0, 1, math.pi, 100), math.pi, radius=2.0)
    assert not wide.holds and "radius 1.00 m; the text asks 2 m" in wide.text


def test_an_arc_is_complete_once_the_turtle_stops():
    poses = circling(5, 5, 1.0, 0, 1, math.pi, 100)
    assert not shapes.arc(poses, math.pi).complete
    assert shapes.arc(poses + [poses[-1]] * (shapes.STILL_POSES + 1), math.pi).complete


@settings(max_examples=60, deadline=None)
@given(CENTRES, CENTRES, HEADINGS, st.floats(0.5, 4.0), DIRECTIONS, st.integers(8, 60), NOISE, SEEDS,
       st.sampled_from((1.0, 1.25, 2.0)))
def test_a_square_is_recognised_with_its_side(x, y, heading, side, direction, steps, noise, seed, laps):
    poses = noisy(squaring(x, y, heading, side, direction, side / steps, laps), noise * side, seed)
    judged = shapes.square(poses, side)
    assert judged.holds and judged.complete, judged.text
    assert shapes.square(poses).holds
    assert ("turning left" if direction > 0 else "turning right") in judged.text


def test_three_sides_are_not_a_square():
    poses = squaring(2, 2, 0, 2.0, 1, 0.05, laps=0.75)
    judged = shapes.square(poses, 2.0)
    assert not judged.holds and not judged.complete and "3 straight sides, not 4" in judged.text


def test_a_square_of_another_side_or_a_rectangle():
    other = shapes.square(squaring(2, 2, 0, 1.0, 1, 0.05, laps=1.25), 2.0)
    assert not other.holds and other.complete and "the text asks 2 m" in other.text
    pentagon = []
    x, y, heading = 2.0, 2.0, 0.0
    for _ in range(5):
        for _ in range(20):
            x, y = x + 0.1 * math.cos(heading), y + 0.1 * math.sin(heading)
            pentagon.append((x, y, wrap(heading)))
        heading += 2 * math.pi / 5
    judged = shapes.square(pentagon)
    assert not judged.holds and "corners turn 1.26" in judged.text


def test_a_zigzag_turns_both_ways():
    poses, x, y = [], 0.0, 0.0
    for dx, dy in ((1, 0), (0, 1), (1, 0), (0, -1)):
        for _ in range(20):
            x, y = x + dx * 0.1, y + dy * 0.1
            poses.append((x, y, math.atan2(dy, dx)))
    judged = shapes.square(poses, 2.0)
    assert not judged.holds and "all the same way" in judged.text


POINTS = st.lists(st.tuples(st.floats(-50, 50), st.floats(-50, 50), st.floats(-math.pi, math.pi)), max_size=60)


@settings(max_examples=150, deadline=None)
@given(POINTS, st.sampled_from(shapes.SHAPES), st.one_of(st.none(), st.floats(0.1, 5)), st.floats(0.01, 0.5))
def test_no_path_makes_a_judgement_raise(poses, shape, size, tolerance):
    judged = shapes.draws(poses, shape, radius=size, angle=size or 1.0, side=size, tolerance=tolerance)
    assert isinstance(judged.text, str) and judged.text
    shapes.fit_circle(shapes.positions(poses))
    shapes.first_outside(poses, Box(0, 11, 0, 11))


@given(st.integers(0, 2), st.tuples(st.floats(-50, 50), st.floats(-50, 50), st.floats(-3, 3)),
       st.integers(0, 100), st.sampled_from(shapes.SHAPES))
def test_few_or_identical_poses_are_judged_not_drawn(count, pose, repeat, shape):
    for poses in ([pose] * count, [pose] * repeat):
        judged = shapes.draws(poses, shape, radius=1.0, angle=1.0, side=1.0)
        assert not judged.holds and not judged.moved and judged.text
        assert shapes.fit_circle(shapes.positions(poses)) is None


def test_turning_in_place_draws_nothing():
    spin = [(5.0, 5.0, wrap(0.1 * i)) for i in range(100)]
    assert shapes.moved(spin)
    assert "turned in place" in shapes.circle(spin).text
    assert not shapes.square(spin).holds


def test_a_straight_line_is_no_arc():
    line = [(0.1 * i, 0.0, 0.0) for i in range(50)]
    assert "straight line" in shapes._fitted(shapes.positions(line), None, 0.15, "arc").text


def test_the_box_edge_is_outside():
    box = Box(0.0, 11.088889, 0.0, 11.088889)
    assert shapes.first_outside([(5, 5, 0), (11.088889, 5, 0), (12, 5, 0)], box) == 1
    assert shapes.first_outside([(5, 5, 0), (6, 6, 0)], box) is None
    assert shapes.first_outside([], box) is None


def test_colours_match_per_channel_and_are_summarised():
    assert shapes.colour_matches((250, 5, 3), (255, 0, 0), 10)
    assert not shapes.colour_matches((179, 184, 255), (255, 0, 0), 10)
    assert shapes.colours_seen([(179, 184, 255)] * 3) == "(179, 184, 255)"
    assert shapes.colours_seen([(255, 0, 0)] * 3 + [(69, 86, 255)]) == "(255, 0, 0) 75%, (69, 86, 255) 25%"
    many = [(i, i, i) for i in range(5)]
    assert shapes.colours_seen(many, most=2).endswith("and 3 others")
    assert shapes.colours_seen([]) == "no colour"


DRAWING_COURSE = """name: t
title: t
milestones:
  - id: a
    title: a
    text: a
    packages: []
    world: [turtlesim]
    steps:
      - draws: {shape: circle, radius: 2}
      - draws: {shape: arc, angle: 1.5, radius: 1}
      - draws: {shape: square, side: 2, within: 40}
      - in_bounds: {for: 3}
      - pen_colour: {r: 255, g: 0, b: 0}
%s"""


def test_the_loader_takes_the_drawing_steps_and_says_what_is_wrong_with_one(tmp_path):
    from course_format import course_file
    assert tuple(course_file.SHAPE_PARAMS) == shapes.SHAPES
    path = tmp_path / "course.yaml"
    path.write_text(DRAWING_COURSE % "")
    assert [s.primitive for s in course_file.load(str(path)).milestones[0].steps] == [
        "draws", "draws", "draws", "in_bounds", "pen_colour"]
    wrong = ["draws: {shape: hexagon}", "draws: {shape: square, radius: 2}", "draws: {shape: arc}",
             "draws: {shape: circle, radius: -1, tolerance: 1.5}", "in_bounds: {xmin: 5, xmax: 4}",
             "pen_colour: {r: 300, g: 0, b: -1}"]
    path.write_text(DRAWING_COURSE % "".join("      - %s\n" % step for step in wrong))
    with pytest.raises(course_file.CourseError) as error:
        course_file.load(str(path))
    said = str(error.value)
    for text in ("'hexagon': a shape is one of circle, arc, square", "a square has no radius (it takes side)",
                 "an arc needs its angle", "draws.radius: -1: expected a number above 0",
                 "tolerance: 1.5: expected a number below 1", "xmax 4 is not above xmin 5",
                 "pen_colour.r: 300: expected a number up to 255",
                 "pen_colour.b: -1: expected a number from 0"):
        assert text in said
