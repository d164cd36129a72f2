"""similarity: what is compared, what is boilerplate, and names a student's package.xml gives."""
import os

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
