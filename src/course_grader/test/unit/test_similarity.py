"""similarity: what is compared, what is boilerplate, and names a student's package.xml gives."""
import os
import shutil

from course_grader import similarity

CODE = '''#!/usr/bin/env python3
import rospy
from std_msgs.msg import String


class Counter:
    def __init__(self, topic):
        self.total = 0
        self.seen = []
        self.sub = rospy.Subscriber(topic, String, self.on_message, queue_size=3)

    def on_message(self, msg):
        self.total += len(msg.data)
        self.seen.append(msg.data[::-1])
        if len(self.seen) > 5:
            self.seen = self.seen[-5:]
        print("%d characters, last reversed: %s" % (self.total, " | ".join(self.seen)))


if __name__ == "__main__":
    rospy.init_node("counter")
    Counter(rospy.get_param("~topic", "/words"))
    rospy.spin()
'''


def _package(root, name="words", script="count.py", text=CODE):
    folder = root / name
    (folder / "scripts").mkdir(parents=True)
    (folder / "package.xml").write_text("<package format='2'><name>%s</name></package>" % name)
    (folder / "scripts" / script).write_text(text)
    return folder


def test_a_renamed_copy_is_flagged_unless_it_is_boilerplate(tmp_path):
    _package(tmp_path / "ann")
    renamed = CODE.replace("Counter", "Tally").replace("total", "count").replace("on_message", "heard")
    _package(tmp_path / "bob", script="tally", text=renamed)  # a #! python script without .py
    students = {"ann": str(tmp_path / "ann"), "bob": str(tmp_path / "bob")}
    pairs = similarity.similar_pairs(students, create_pkg=False)
    assert [(p.student_a, p.student_b, p.package) for p in pairs] == [("ann", "bob", "words")]
    assert pairs[0].score > 0.9 and "Tally" in pairs[0].shared[0].right
    _package(tmp_path / "given")
    assert similarity.similar_pairs(students, [str(tmp_path / "given")], create_pkg=False) == []


def test_links_and_other_files_are_not_read(tmp_path):
    folder = _package(tmp_path / "ann")
    os.symlink("/etc/passwd", str(folder / "scripts" / "stolen.py"))
    (folder / "notes.txt").write_text("not code")
    assert set(similarity.package_documents(str(folder))) == {"python"}
    assert "root:" not in similarity.package_documents(str(folder))["python"]


def test_only_valid_package_names_reach_catkin_create_pkg(tmp_path):
    made = tmp_path / "made"
    made.mkdir()
    similarity.created_package(["chatter", "../escaped", "-h", "Bad"], str(made))
    assert sorted(os.listdir(str(made))) == ["chatter"] and not (tmp_path / "escaped").exists()
    assert (made / "chatter" / "CMakeLists.txt").is_file()


OTHER_SERVER = '''#!/usr/bin/env python3
"""One Patrol server per turtle named on the command line."""
import sys

import rospy
from geometry_msgs.msg import Twist
from turtlesim.srv import TeleportAbsolute
from turtle_patrol.srv import Patrol, PatrolResponse

turtle = rospy.myargv(sys.argv)[1]
rospy.init_node("patrol_" + turtle)
pub = rospy.Publisher("/%s/cmd_vel" % turtle, Twist, queue_size=5)
teleport = rospy.ServiceProxy("/%s/teleport_absolute" % turtle, TeleportAbsolute)
state = {"twist": Twist()}


def handle(req):
    teleport(req.x, req.y, req.theta)
    state["twist"].linear.x, state["twist"].angular.z = req.vel, req.omega
    return PatrolResponse(state["twist"])


rospy.Service("/%s/patrol" % turtle, Patrol, handle)
rate = rospy.Rate(20)
while not rospy.is_shutdown():
    pub.publish(state["twist"])
    rate.sleep()
'''


def test_the_code_a_course_hands_out_is_boilerplate(tmp_path):
    """Lab 2's students keep the starter's patrol_client.py and Patrol.srv as handed out (the text says
    not to edit the client): two servers written apart are no pair once the course's starter/ is
    boilerplate, as `grade` makes it (cli.boilerplate_folders)."""
    from course_grader import cli
    from course_format import course_file
    course = course_file.load(course_file.builtin_course_dir())
    starter = os.path.join(course.starter, "lab2", "src", "turtle_patrol")
    students = {}
    for name, server in (("ann", CODE), ("bob", OTHER_SERVER)):
        folder = tmp_path / name / "turtle_patrol"
        shutil.copytree(starter, str(folder))
        (folder / "src" / "patrol_server.py").write_text(server)
        students[name] = str(tmp_path / name)
    alike = similarity.similar_pairs(students, threshold=0.0, create_pkg=False)
    left = similarity.similar_pairs(students, cli.boilerplate_folders(course), threshold=0.0, create_pkg=False)
    print("starter alone: %.2f; with the starter as boilerplate: %s" % (alike[0].score, left and left[0].score))
    assert alike[0].package == "turtle_patrol" and alike[0].score > 0.3  # the handout alone makes them alike
    assert not left or left[0].score < 0.1
    assert course.starter in cli.boilerplate_folders(course, ["/given"])
