#!/usr/bin/env python3
"""Milestone `checkpoint3` (002 section 5, checkpoint 3): the modified patrol service makes several
turtles patrol circles from the initial poses given in their calls,
`rosservice call /<turtle>/patrol vel omega x y theta`.

The text leaves open which script is the server, whether one server serves every turtle or
one runs per turtle (its hint: pass the turtle's name as an argument), and whether the service's
name or its request names the turtle (the call "may look like" the one it shows). So the check
starts the package's executables with the turtle names as arguments until one offers a patrol
service. A server offering /<turtle>/patrol gets one more copy per turtle still unserved; one
offering a shared patrol service is called with each turtle's name in its request's string
field (patrol.py). Each call runs in a thread: a server built on the lab's
starter code publishes inside its callback and never returns, and the text asks for motion, not
a reply. Each turtle is judged by its poses: it starts at (x, y), circles the centre its start
heading implies, at the requested speeds, and keeps going."""
import math
import threading
from typing import Dict, List, NamedTuple

import rospy
import rostest
from turtlesim.msg import Pose as PoseMsg
from turtlesim.srv import Spawn

from course_rospy import quick_exit
from course_format import causes
from course_milestones import guard, messages, students
import patrol
from circles import PatrolRequest, Pose, farthest_off_circle, observed_centre, start_index
from course_milestones.discovery import MASTER_POLL_S, script_hints, list_executables, system_state, unbuilt_problems
from course_milestones.milestone_case import MilestoneCase
from course_milestones.trusted import TURTLESIM
from course_checks.artifacts import save_canvas
from course_checks.recorders import TopicRecorder
from course_checks.waiting import wait_for

SPAWNED = {"turtle2": (2.0, 2.0, 0.0), "turtle3": (9.0, 2.0, 0.0)}
REQUESTS = {"turtle1": PatrolRequest(1.0, 1.0, 3.0, 3.0, 1.57),
            "turtle2": PatrolRequest(1.5, -1.0, 8.0, 8.0, -1.0),
            "turtle3": PatrolRequest(2.0, 1.5, 3.0, 8.0, 2.5)}
PATROL_S = 2.5  # observed patrol per turtle: more than turtlesim's 1 s command time-out
POSE_HZ = 62.5
TOLERANCE_M = 0.3
SPEED_TOLERANCE = 0.05


def service_name(turtle: str) -> str:
    return "/%s/patrol" % turtle


def offered_services():
    return {s for reg in system_state().values() for s in reg.services}


def call_text(turtle: str, req: PatrolRequest) -> str:
    """The text's call for `turtle`."""
    return "rosservice call %s %g %g %g %g %g" % ((service_name(turtle),) + tuple(req))


def is_patrol(service: str) -> bool:
    return service.rsplit("/", 1)[-1].endswith("patrol")


class Target(NamedTuple):
    """Where a turtle's patrol is asked: the service and how its request is filled."""

    service: str
    layout: patrol.Layout
    service_class: type

    def call_text(self, turtle: str, req: PatrolRequest) -> str:
        return patrol.call_words(self.service, self.layout, turtle, req)


class Call(threading.Thread):
    """One service call that may never return (the starter server loops inside its callback)."""

    def __init__(self, proxy, arguments: List[object]) -> None:
        super().__init__(daemon=True)
        self.proxy, self.arguments, self.error = proxy, arguments, None

    def run(self) -> None:
        try:
            self.proxy(*self.arguments)
        except Exception as err:  # noqa: BLE001 - the student's server refused or died
            self.error = err


@guard.judged  # a violation of the trust policy fails the test, first
class CheckpointThree(MilestoneCase):

    def setUp(self):
        self.started = []
        self.known = {}
        rospy.wait_for_service("/spawn", 30)
        for name, pose in SPAWNED.items():
            rospy.ServiceProxy("/spawn", Spawn)(*pose, name)
        self.poses = {t: TopicRecorder("/%s/pose" % t, PoseMsg) for t in REQUESTS}

    def tearDown(self):
        save_canvas()
        students.end_all(self.started)

    def server_output(self) -> str:
        return " | ".join("%s: %r" % (s.name, s.node.output()[-300:]) for s in self.started)

    def start_server(self, pkg: str):
        """The first executable (likely servers first) that offers a patrol service when started with
        the turtle names as arguments; None and what each did otherwise."""
        tried = []
        for path in students.servers_first(list_executables(pkg)):
            for args in (list(REQUESTS), list(REQUESTS)[:1]):  # a server for one turtle may refuse three names
                candidate = students.start(path, args)
                found = students.find_role([candidate], lambda r: any(is_patrol(s) for s in r.services), 20,
                                           self.known, settle=3.0)
                if found:
                    self.started.append(candidate)
                    return candidate, ""
                exited = not candidate.node.running()
                tried.append("%s (started with %s)" % (students.describe([candidate], self.known), " ".join(args)))
                students.stop_all([candidate])
                if not exited:
                    break
        return None, "; ".join(tried) or "no executables%s" % script_hints(pkg)

    def serve_every_turtle(self, pkg: str, server) -> str:
        """Start one more server per turtle not served yet, one at a time (a copy that takes another's
        node name ends it: what each copy offers is read while it runs); 'one server for all' or
        'one per turtle'."""
        missing = [t for t in REQUESTS
                   if not wait_for(lambda t=t: service_name(t) in offered_services(), 1.0, MASTER_POLL_S)]
        first = students.did(server, self.known)
        for turtle in missing:
            extra = students.start(server.path, [turtle])
            self.started.append(extra)
            found = students.find_role([extra], lambda r, t=turtle: service_name(t) in r.services, 20, self.known,
                                       settle=3.0)
            if not found:
                did = students.did(extra, self.known)
                other = [service_name(t) for t in REQUESTS if t != turtle and service_name(t) in did]
                self.fail(causes.finding("no_service", "%s: no %s service. Started with %s, the server %s; started as "
                                         "`rosrun %s %s %s`, it %s%s" % (
                    turtle, service_name(turtle), " ".join(server.node.command[1:]), first, pkg, server.name, turtle,
                    did, " (another turtle's service than its argument names: build the service's name from the "
                         "argument, e.g. '/%s/patrol' % name)" if other else "")))
        for s in self.started:
            self.assertTrue(s.node.running() and students.SAME_NAME not in s.node.output(),
                            causes.finding(causes.exited(False),  # no patrol was asked of it yet
                                           "the patrol server %s (%s) stopped when another one "
                                           "started%s" % (s.name, " ".join(s.node.command[1:]),
                                                          students.last_words(s))))
        return "one server per turtle" if missing else "one server for all turtles, a /<turtle>/patrol service each"

    def targets(self, pkg: str, server) -> Dict[str, Target]:
        """Each turtle's service and request layout: per turtle when the server offers
        /<turtle>/patrol (more copies started as needed), else its shared patrol service."""
        offered = sorted({s for r in students.registrations_of(server, self.known) for s in r.services if is_patrol(s)})
        per_turtle = [s for s in offered if s in {service_name(t) for t in REQUESTS}]
        design = self.serve_every_turtle(pkg, server) if per_turtle or not offered else ""
        services = {t: service_name(t) for t in REQUESTS} if design else dict.fromkeys(REQUESTS, offered[0])
        found: Dict[str, Target] = {}
        for turtle, service in services.items():
            known = next((t for t in found.values() if t.service == service), None)  # a shared service: once
            found[turtle] = known or self.target(server, service, turtle, named_by_service=bool(design))
        if not design:
            design = "one %s service for all turtles, the turtle named in its request's field %s" % (
                offered[0], found["turtle1"].layout.name_field)
        print("server: %s, %s" % (server.name, design))
        return found

    def target(self, server, service: str, turtle: str, named_by_service: bool) -> Target:
        """`service`'s type loaded from the running server and how the text's call fills its request."""
        try:
            service_class = messages.service_class_by_name(service)
        except messages.InterfaceError as err:
            self.fail(causes.finding(err.cause, "cannot load the type of %s: %s; server output: %s"
                                     % (service, err, self.server_output())))
        request = service_class._request_class
        plan, problem = patrol.layout(request.__slots__, request._slot_types, named_by_service)
        if problem:
            self.fail(causes.finding("wrong_type", "the patrol server %s (started with %s) offers %s: %s; the text's "
                                     "call is `%s`" % (server.name, " ".join(server.node.command[1:]), service,
                                                       problem, call_text(turtle, REQUESTS[turtle]))))
        return Target(service, plan, service_class)

    def test_turtles_patrol_from_their_poses(self):
        pkg = rospy.get_param("~pkg")
        server, tried = self.start_server(pkg)
        if not server:  # a service type the package never built comes first: it is the cause to fix
            unbuilt = unbuilt_problems(pkg)
            self.fail(causes.finding(causes.of(unbuilt[0], "not_generated") if unbuilt
                                     else students.start_cause(pkg, default="no_service"), "\n".join(unbuilt + [
                                         "no executable in package %s offers a patrol service when started with the "
                                         "turtle names as arguments (%s)" % (pkg, tried)])))
        targets = self.targets(pkg, server)
        calls = {}
        for turtle, req in REQUESTS.items():
            target = targets[turtle]
            self.poses[turtle].clear()
            calls[turtle] = Call(rospy.ServiceProxy(target.service, target.service_class),
                                 target.layout.arguments(turtle, req))
            calls[turtle].start()
            started = wait_for(lambda t=turtle: calls[t].error or start_index(self.pose_list(t), REQUESTS[t])
                               is not None, 10)
            asked = target.call_text(turtle, req)
            self.assertIsNone(calls[turtle].error,
                              causes.finding("wrong_answer", "`%s` failed: %s" % (asked, calls[turtle].error)))
            self.assertTrue(started, causes.finding("not_moving", "after `%s`, %s never came to (%g, %g); server "
                                                    "output: %s" % (asked, turtle, req.x, req.y, self.server_output())))
        enough = int(PATROL_S * POSE_HZ * 0.9)
        wait_for(lambda: all(len(self.patrol(t)) >= enough for t in REQUESTS), PATROL_S * 3)
        for turtle, req in REQUESTS.items():
            self.check_patrol(turtle, req, targets[turtle].call_text(turtle, req))
        for turtle, call in calls.items():
            if call.is_alive():
                print("note: the call to %s never returned (its server keeps publishing inside the service "
                      "callback); the turtle's motion was judged instead" % targets[turtle].service)

    def pose_list(self, turtle: str):
        return [Pose(p.x, p.y, p.theta) for p in self.poses[turtle].messages]

    def patrol(self, turtle: str):
        poses = self.pose_list(turtle)
        i = start_index(poses, REQUESTS[turtle])
        return [] if i is None else poses[i:]

    def check_patrol(self, turtle: str, req: PatrolRequest, call: str) -> None:
        patrol = self.patrol(turtle)
        asked = "`%s`" % call
        self.assertGreater(len(patrol), 10,
                           causes.finding("not_moving", "%s: too few poses after %s" % (turtle, asked)))
        last = self.poses[turtle].last
        self.assertTrue(abs(last.linear_velocity - req.vel) < SPEED_TOLERANCE
                        and abs(last.angular_velocity - req.omega) < SPEED_TOLERANCE,
                        causes.finding("not_moving", "%.1f s after %s, %s moves at linear %.2f, angular %.2f: it "
                                       "should keep patrolling at %g, %g (turtlesim stops a turtle 1 s after its last "
                                       "command)" % (len(patrol) / POSE_HZ, asked, turtle, last.linear_velocity,
                                                     last.angular_velocity, req.vel, req.omega)))
        centre, expected = observed_centre(patrol, req), req.centre()
        self.assertLess(math.hypot(centre[0] - expected[0], centre[1] - expected[1]), TOLERANCE_M,
                        causes.finding("wrong_value", "after %s, %s circles around (%.2f, %.2f), not around (%.2f, "
                                       "%.2f) where a patrol starting at (%g, %g) heading %g rad goes: is the start "
                                       "heading theta used?" % (asked, turtle, centre[0], centre[1], expected[0],
                                                                expected[1], req.x, req.y, req.theta)))
        off = farthest_off_circle(patrol, req)
        self.assertLess(off, TOLERANCE_M, causes.finding(
            "wrong_value", "after %s, %s strays %.2f m from the circle of radius %.2f around (%.2f, %.2f)"
            % (asked, turtle, off, req.radius(), expected[0], expected[1])))


if __name__ == "__main__":
    quick_exit.install()  # before init_node: rospy's exit without a spinning core
    rospy.init_node("checkpoint3_check")
    guard.install([TURTLESIM])  # before any student code: believe only this simulator
    rostest.rosrun("course_milestones", "checkpoint3_check", CheckpointThree)
