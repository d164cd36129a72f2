"""KeyMapSearch against simulated controllers: which keys it finds, in how many presses, and the
sentence a student reads when a direction is missing."""
import math

import pytest
from hypothesis import given, settings, strategies as st

from course_format import causes

import keymap as km

ARROWS = {"up": (2.0, 0.0), "down": (-2.0, 0.0), "left": (0.0, 2.0), "right": (0.0, -2.0)}
WASD = {"w": (1.0, 0.0), "s": (-1.0, 0.0), "a": (0.0, 1.0), "d": (0.0, -1.0)}


class FakeController:
    """Answers a press with the command its map gives (key -> (linear.x, angular.z[, linear.y]));
    `line` controllers need Enter, the others read single keys (their terminal is in raw mode);
    `quits_on` keys make it exit (a restart brings it back)."""

    def __init__(self, keys, line=False, quits_on=(), continuous=False):
        self.keys, self.line, self.continuous = keys, line, continuous
        self.quits_on = {quits_on} if isinstance(quits_on, str) else set(quits_on)
        self.presses = []
        self.state = km.Command(0.0, 0.0)
        self.running = True
        self.restarts = 0

    @property
    def seen_raw(self):
        return not self.line and bool(self.presses)

    def restart(self):
        self.running, self.state = True, km.Command(0.0, 0.0)
        self.restarts += 1

    def press(self, probe):
        assert self.running, "a key typed into a node that exited"
        self.presses.append(probe)
        if probe.key in self.quits_on:
            self.running = False
            return km.Outcome((), exited=True)
        command = self.keys.get(probe.key) if probe.enter == self.line else None
        if command is None:
            return km.Outcome((self.state,) * 3 if self.continuous else ())
        self.state = km.Command(command[0], command[1], *command[2:])
        return km.Outcome((self.state,) * (3 if self.continuous else 1))


def search(controller, **kwargs):
    """The ROS side's loop (keyboard_probe._search) without ROS."""
    s = km.KeyMapSearch(**kwargs)
    while True:
        if s.restart_due:
            controller.restart()
            s.restarted()
        probe = s.next_probe()
        if probe is None:
            return s.result()
        if not s.suits(probe, controller.seen_raw):
            s.skip()
            continue
        s.record(probe, controller.press(probe))


def test_arrows_found_in_four_presses():
    ctrl = FakeController(ARROWS)
    result = search(ctrl)
    assert result.complete
    assert result.keymap.keys == {km.FORWARD: "up", km.BACKWARD: "down", km.LEFT: "left", km.RIGHT: "right"}
    assert not result.keymap.enter
    assert len(ctrl.presses) == 4
    assert km.failure_message(result, "/turtle1/cmd_vel", "turtle1") is None


def test_wasd_with_enter_like_input():
    ctrl = FakeController(WASD, line=True)
    result = search(ctrl)
    assert result.complete and result.keymap.enter and result.keymap.layout == "w/a/s/d"
    assert result.keymap.describe() == "w/a/s/d + Enter (forward='w', backward='s', left='a', right='d')"
    # up, up+Enter, w, then w+Enter answers, and again when pressed once more; then s, a, d with Enter
    assert [(p.key, p.enter) for p in ctrl.presses[:5]] == [("up", False), ("up", True), ("w", False), ("w", True),
                                                            ("w", True)]
    assert result.presses == len(ctrl.presses) == 8


def test_wasd_with_x_backwards():
    keys = dict(WASD, x=(-1.0, 0.0))
    keys["s"] = (0.0, 0.0)  # s stops, as in turtlebot3_teleop_key
    result = search(FakeController(keys))
    assert result.complete and result.keymap.keys[km.BACKWARD] == "x"


def test_azerty_q_is_left_only_after_z_went_forward():
    keys = {"z": (1.0, 0.0), "s": (-1.0, 0.0), "q": (0.0, 1.0), "d": (0.0, -1.0)}
    ctrl = FakeController(keys)
    result = search(ctrl)
    assert result.complete and result.keymap.layout == "z/q/s/d"
    assert [p.key for p in ctrl.presses].index("q") > [p.key for p in ctrl.presses].index("z")


def test_ijkl_and_continuous_publishing():
    keys = {"i": (0.5, 0.0), ",": (-0.5, 0.0), "j": (0.0, 1.0), "l": (0.0, -1.0), "k": (0.0, 0.0)}
    result = search(FakeController(keys, continuous=True))
    assert result.complete and result.keymap.keys == {km.FORWARD: "i", km.BACKWARD: ",", km.LEFT: "j",
                                                      km.RIGHT: "l"}


def test_back_and_right_doing_nothing_fails_naming_the_keys():
    keys = {"up": (2.0, 0.0), "left": (0.0, 2.0)}
    ctrl = FakeController(keys)
    result = search(ctrl)
    assert not result.complete
    assert set(result.missing) == {km.BACKWARD, km.RIGHT}
    message = km.failure_message(result, "/turtle1/cmd_vel", "turtle1")
    assert "no key made turtle1 go backward: after pressing down, 's', 'x', 'k' and " in message
    assert "more keys, /turtle1/cmd_vel got no command with linear.x < 0" in message
    assert "no key made turtle1 turn right: after pressing right, 'd', 'l', '6' and " in message
    # each silent key is pressed twice (a press can be lost while the node sets up its terminal)
    assert sum(1 for p in ctrl.presses if p.key == "down") == 2


def test_wrong_sign_is_reported_with_the_command_seen():
    keys = dict(ARROWS, right=(0.0, 2.0))  # right turns left
    result = search(FakeController(keys))
    message = km.failure_message(result, "/t/cmd_vel", "t")
    assert "turn right" in message and "angular.z < 0" in message and "angular.z=2" in message


def test_a_slow_answer_is_not_taken_for_the_next_key():
    class Slow(FakeController):
        """Answers 'up' one press late, as a node too slow for the probe window would."""

        def press(self, probe):
            self.presses.append(probe)
            late = len(self.presses) >= 2 and self.presses[-2].key == "up" and not self.presses[-2].enter
            return km.Outcome((km.Command(2.0, 0.0),) if late else ())
    ctrl = Slow({}, line=True)
    result = search(ctrl)
    assert result.keymap is None  # up + Enter got up's answer once, but not again: not taken
    assert ctrl.presses[1] == ctrl.presses[2] == km.Probe(km.FORWARD, "up", True)


FORWARD_KEYS = sum(len(layout.keys[km.FORWARD]) for layout in km.LAYOUTS)


@pytest.mark.parametrize("line", [False, True])
def test_nothing_moves_the_turtle(line):
    ctrl = FakeController({}, line=line)
    result = search(ctrl)
    assert result.keymap is None
    message = km.failure_message(result, "/turtle1/cmd_vel", "turtle1")
    assert message.startswith("no key made turtle1 go forward, go backward, turn left or turn right: after each of "
                              + ("up, up + Enter, 'w', 'w' + Enter and " if line else "up, 'w', 'z', 'i' and "))
    assert message.endswith("more keys, /turtle1/cmd_vel got no command with linear.x > 0, linear.x < 0, "
                            "angular.z > 0 or angular.z < 0 (commands seen: none)")
    # the layouts' forward keys twice (alone, and + Enter while no raw mode was seen), then every other key once
    first_rounds = 4 * FORWARD_KEYS if line else 2 * FORWARD_KEYS
    assert len(ctrl.presses) == first_rounds + len(km.ALL_KEYS) - FORWARD_KEYS
    assert {p.key for p in ctrl.presses} == set(km.ALL_KEYS)


def test_node_exiting_on_a_key_is_started_again():
    ctrl = FakeController(WASD, quits_on="up")
    result = search(ctrl)
    assert result.complete and result.keymap.keys[km.FORWARD] == "w" and ctrl.restarts == 1
    assert result.exited_on == (km.Probe(km.FORWARD, "up", False),)


def test_node_exiting_on_every_key_stops_the_search():
    ctrl = FakeController({}, quits_on=km.ALL_KEYS)
    result = search(ctrl)
    assert ctrl.restarts == km.MAX_RESTARTS and len(result.exited_on) == km.MAX_RESTARTS + 1
    assert result.exited_after == result.exited_on[-1]
    message = km.failure_message(result, "/turtle1/cmd_vel", "turtle1")
    # no key moved the turtle before it exited: it never did what was asked
    assert message.cause == "exited_early" and "exited after the key" in message and "so far: none" in message


def test_node_exiting_after_a_key_that_moved_the_turtle_did_some_of_it():
    ctrl = FakeController({"w": (1.0, 0.0)}, quits_on=[k for k in km.ALL_KEYS if k != "w"])
    result = search(ctrl)
    assert result.keymap is not None and result.exited_after is not None
    message = km.failure_message(result, "/turtle1/cmd_vel", "turtle1")
    assert message.cause == "node_exited" and "exited after the key" in message


def test_a_missing_turn_names_the_key_that_quit():
    keys = {"w": (1.0, 0.0), "s": (-1.0, 0.0), "a": (0.0, 1.0)}
    result = search(FakeController(keys, quits_on="q"))
    message = km.failure_message(result, "/turtle1/cmd_vel", "turtle1")
    assert "no key made turtle1 turn right" in message and "exited after 'q' and was started again" in message


def test_inverted_turns_are_found():
    """w/s forward and backward, d turns left and a right: the text fixes the motions, not the keys."""
    keys = {"w": (1.0, 0.0), "s": (-1.0, 0.0), "d": (0.0, 1.0), "a": (0.0, -1.0)}
    ctrl = FakeController(keys, line=True)
    result = search(ctrl)
    assert result.complete
    assert result.keymap.keys == {km.FORWARD: "w", km.BACKWARD: "s", km.LEFT: "d", km.RIGHT: "a"}
    assert result.keymap.describe() == "custom + Enter (forward='w', backward='s', left='d', right='a')"
    assert result.presses == 8  # up, up + Enter, w, w + Enter twice, s, a, d
    assert km.failure_message(result, "/turtle1/cmd_vel", "turtle1") is None


def test_strafing_shows_linear_y():
    keys = {"w": (1.0, 0.0), "s": (-1.0, 0.0), "a": (0.0, 0.0, 1.0), "d": (0.0, 0.0, -1.0)}
    result = search(FakeController(keys))
    message = km.failure_message(result, "/turtle1/cmd_vel", "turtle1")
    assert "no key made turtle1 turn left" in message and "no key made turtle1 turn right" in message
    assert "linear.x=0 linear.y=1 angular.z=0" in message and "linear.x=0 linear.y=-1 angular.z=0" in message


def test_keys_shown_to_make_no_motion_before_the_first_find_are_not_pressed_again():
    # up and down strafe, left and right turn: found last among every key (the arrows), so every
    # letter and digit was already pressed once and made nothing
    keys = {"up": (0.0, 0.0, 2.0), "down": (0.0, 0.0, -2.0), "left": (0.0, 2.0), "right": (0.0, -2.0)}
    ctrl = FakeController(keys)
    result = search(ctrl)
    assert set(result.missing) == {km.FORWARD, km.BACKWARD}
    letters = [p.key for p in ctrl.presses if len(p.key) == 1]
    forward_keys = {k for layout in km.LAYOUTS for k in layout.keys[km.FORWARD]}  # pressed `rounds` times
    assert all(letters.count(k) == 1 for k in letters if k not in forward_keys)  # not once per search
    message = km.failure_message(result, "/turtle1/cmd_vel", "turtle1")
    # the reason still names what was pressed before the turns were found
    assert "no key made turtle1 go forward: after pressing up, 'w', 'z', 'i' and 37 more keys" in message
    assert "no key made turtle1 go backward: after pressing 's', 'x', 'k', ',' and 37 more keys" in message
    assert "linear.x=0 linear.y=2 angular.z=0" in message


def test_a_key_silent_before_the_first_find_is_still_tried_when_it_is_the_layouts():
    # 's' goes backward only once 'w' has been pressed (a node that arms on its first key): the
    # preferred layout's keys are pressed again after the first find, every other key is not
    class Arming(FakeController):
        def press(self, probe):
            if probe.key == "s" and not any(p.key == "w" for p in self.presses):
                self.presses.append(probe)
                return km.Outcome(())
            return super().press(probe)
    keys = {"w": (1.0, 0.0), "s": (-1.0, 0.0), "a": (0.0, 1.0), "d": (0.0, -1.0)}
    result = search(Arming(keys))
    assert result.complete and result.keymap.keys == {km.FORWARD: "w", km.BACKWARD: "s", km.LEFT: "a",
                                                      km.RIGHT: "d"}


def test_command_describes_every_field_that_is_not_zero():
    assert km.Command(0.0, 0.0).describe() == "linear.x=0 angular.z=0"
    assert km.Command(1.0, -0.5, 0.0, 2.0, 0.0, 3.0).describe() == "linear.x=1 linear.z=2 angular.y=3 angular.z=-0.5"


MOTIONS = {km.FORWARD: (1.5, 0.0), km.BACKWARD: (-1.5, 0.0), km.LEFT: (0.0, 2.0), km.RIGHT: (0.0, -2.0)}


@st.composite
def key_maps(draw, directions=km.DIRECTIONS):
    """A controller's map: distinct keys of the sets the search tries for `directions`, read as
    single keys or lines, published once or all the time, maybe with a key that quits."""
    keys = draw(st.lists(st.sampled_from(km.ALL_KEYS), min_size=len(directions), max_size=len(directions),
                         unique=True))
    scale = draw(st.floats(0.1, 5.0))
    mapping = {k: (MOTIONS[d][0] * scale, MOTIONS[d][1] * scale) for k, d in zip(keys, directions)}
    others = [k for k in km.ALL_KEYS if k not in mapping]
    stop = draw(st.none() | st.sampled_from(others))
    if stop is not None:
        mapping[stop] = (0.0, 0.0)
    quits = draw(st.none() | st.sampled_from([k for k in others if k != stop]))
    return mapping, dict(zip(directions, keys)), quits, draw(st.booleans()), draw(st.booleans())


@settings(max_examples=300, deadline=None)
@given(key_maps())
def test_any_four_distinct_keys_are_found(drawn):
    mapping, expected, quits, line, continuous = drawn
    result = search(FakeController(mapping, line=line, quits_on=quits or (), continuous=continuous))
    assert result.complete, km.failure_message(result, "/t/cmd_vel", "t")
    assert result.keymap.keys == expected and result.keymap.enter == line
    assert km.failure_message(result, "/t/cmd_vel", "t") is None


@settings(max_examples=200, deadline=None)
@given(st.sampled_from(km.DIRECTIONS).flatmap(
    lambda gone: st.tuples(st.just(gone), key_maps(tuple(d for d in km.DIRECTIONS if d != gone)))))
def test_a_missing_motion_fails_naming_it(drawn):
    gone, (mapping, _, quits, line, continuous) = drawn
    result = search(FakeController(mapping, line=line, quits_on=quits or (), continuous=continuous))
    assert not result.complete and set(result.missing) == {gone}
    message = km.failure_message(result, "/t/cmd_vel", "t")
    assert message.cause == "not_moving" and "no key made t %s:" % km.WORDS[gone] in message


def test_first_keymap_is_tried_first():
    first = km.KeyMap("w/a/s/d", {km.FORWARD: "w", km.BACKWARD: "s", km.LEFT: "a", km.RIGHT: "d"}, True)
    ctrl = FakeController(WASD, line=True)
    result = search(ctrl, first=first)
    assert result.complete and len(ctrl.presses) == 4


@pytest.mark.parametrize("direction,lin,ang,ok", [
    (km.FORWARD, 1.0, 0.0, True), (km.FORWARD, -1.0, 0.0, False), (km.BACKWARD, -0.1, 0.0, True),
    (km.LEFT, 0.0, 0.5, True), (km.LEFT, 1.0, 0.5, True), (km.RIGHT, 0.0, 0.5, False),
    (km.FORWARD, math.nan, 0.0, False),
])
def test_answers(direction, lin, ang, ok):
    assert km.answers(direction, lin, ang) is ok


def test_moved_along_heading_and_turns():
    start = (5.0, 5.0, math.pi / 2)
    assert km.moved(km.FORWARD, start, (5.0, 5.3, math.pi / 2), 0.05, 0.05)
    assert km.moved(km.BACKWARD, start, (5.0, 4.7, math.pi / 2), 0.05, 0.05)
    assert not km.moved(km.FORWARD, start, (5.3, 5.0, math.pi / 2), 0.05, 0.05)
    assert km.moved(km.LEFT, (0, 0, 3.1), (0, 0, -3.1), 0.05, 0.05)  # across the wrap
    assert km.moved(km.RIGHT, (0, 0, 0.2), (0, 0, 0.0), 0.05, 0.05)


def test_stale_bytes_risk_after_an_unanswered_arrow():
    up, w, w_line = km.Probe(km.FORWARD, "up", False), km.Probe(km.FORWARD, "w", False), km.Probe(km.FORWARD, "w", True)
    assert km.stale_bytes_risk([up], w) and km.stale_bytes_risk([up], w_line)
    assert not km.stale_bytes_risk([], w)
    assert not km.stale_bytes_risk([km.Probe(km.FORWARD, "up", True)], w)  # a line: Ctrl+U dropped it
    assert not km.stale_bytes_risk([up], km.Probe(km.BACKWARD, "down", False))


def test_skip_drops_the_next_probe_unpressed():
    s = km.KeyMapSearch()
    s.record(s.next_probe(), km.Outcome())  # up: nothing
    assert s.next_probe() == km.Probe(km.FORWARD, "up", True)
    s.skip()
    assert s.next_probe() == km.Probe(km.FORWARD, "w", False) and s.result().presses == 1


def test_keymap_failures_carry_not_moving():  # the checks fail with it as their message (test_check_causes)
    result = km.SearchResult(keymap=None, missing={km.FORWARD: []}, exited_after=None, commands={})
    message = km.failure_message(result, "/turtle1/cmd_vel", "turtle1")
    assert causes.of(message) == "not_moving" and message.startswith("no key made turtle1 go forward")
