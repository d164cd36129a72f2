"""messages builds message and service classes from definitions, never importing a student's package.

What must hold: the class carries the md5 and full text genpy's generated class has (else it cannot
talk to the student's nodes); a package whose __init__.py has a side effect is never imported;
a definition made to run code when pasted into genpy's source runs nothing; and any definition
text gives a class or an InterfaceError sentence, never another exception."""
import importlib
import importlib.util
import io
import os
import shutil
import subprocess
import sys
import uuid

import genmsg
import genmsg.msg_loader
import genpy.dynamic
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from course_milestones import messages

GENMSG_PY = "/usr/lib/genpy/genmsg_py.py"
GENSRV_PY = "/usr/lib/genpy/gensrv_py.py"

THING = """# A message of the kinds of fields and constants genpy handles.
# Quotes in comments: "", ''' and \"\"\" are fine.
Header header
int8 SMALL=-3   # a comment after a constant
uint8 BYTE=255
float64 RATIO=1.5e3
bool YES=True
string GREETING=it's "quoted" # not a comment
string EMPTY=
int32 count
float32[3] vec
uint8[] blob
uint8[4] four
string[] words
time stamp
duration wait
geometry_msgs/Point point
Other[] others
Other[2] pair
"""
OTHER = "string name\nint64 value\n"
ASK = "# a service\nint32 a\nOther b\n---\nstring answer\nbool ok\n"


@pytest.fixture(autouse=True)
def fresh_caches():
    messages.forget()
    yield
    messages.forget()


def generate_with_genpy(pkg: str, msg_dir: str, srv_dir: str, out: str) -> None:
    """Build `pkg`'s Python as catkin does (genpy's own scripts), into `out`/pkg."""
    includes = ["-I%s:%s" % (pkg, msg_dir), "-Istd_msgs:/usr/share/std_msgs/msg",
                "-Igeometry_msgs:/usr/share/geometry_msgs/msg"]
    for script, kind, folder in ((GENMSG_PY, "msg", msg_dir), (GENSRV_PY, "srv", srv_dir)):
        target = os.path.join(out, pkg, kind)
        files = sorted(os.path.join(folder, f) for f in os.listdir(folder))
        for path in files:
            subprocess.run([sys.executable, script, "-p", pkg, *includes, "-o", target, path], check=True)
        subprocess.run([sys.executable, script, "--initpy", "-p", pkg, "-o", target], check=True)


@pytest.fixture
def student_package(tmp_path, monkeypatch):
    """A built package as an overlay gives it: definitions under ROS_PACKAGE_PATH, generated Python
    on sys.path, and an __init__.py that writes a file when imported."""
    pkg = "tmp_msgs_%s" % uuid.uuid4().hex[:8]
    root = tmp_path / "src" / pkg
    (root / "msg").mkdir(parents=True)
    (root / "srv").mkdir()
    (root / "package.xml").write_text('<package format="2"><name>%s</name><version>0.0.0</version>'
                                      '<description>t</description><maintainer email="a@b.c">a</maintainer>'
                                      '<license>BSD</license></package>' % pkg)
    (root / "msg" / "Thing.msg").write_text(THING)
    (root / "msg" / "Other.msg").write_text(OTHER)
    (root / "srv" / "Ask.srv").write_text(ASK)
    devel = tmp_path / "devel"  # a devel space: its marker names the source folder it built
    site = devel / "lib" / "python3" / "dist-packages"
    generate_with_genpy(pkg, str(root / "msg"), str(root / "srv"), str(site))
    (devel / ".catkin").write_text(str(tmp_path / "src"))
    marker = tmp_path / "imported"
    (site / pkg / "__init__.py").write_text("open(%r, 'w').write('imported')\n" % str(marker))
    monkeypatch.setenv("ROS_PACKAGE_PATH", "%s:%s" % (tmp_path / "src", os.environ.get("ROS_PACKAGE_PATH", "")))
    monkeypatch.setenv("CMAKE_PREFIX_PATH", "%s:%s" % (devel, os.environ.get("CMAKE_PREFIX_PATH", "")))
    monkeypatch.syspath_prepend(str(site))
    importlib.invalidate_caches()
    yield pkg, marker
    for name in [m for m in sys.modules if m == pkg or m.startswith(pkg + ".")]:
        del sys.modules[name]


def test_student_package_is_never_imported_and_classes_match_genpy(student_package):
    pkg, marker = student_package
    assert not messages.imports_safely(pkg)
    thing = messages.message_class("%s/Thing" % pkg)
    ask = messages.service_class("%s/Ask" % pkg)
    assert not marker.exists(), "the student's __init__.py ran in the check's process"
    assert pkg not in sys.modules

    generated = importlib.import_module("%s.msg" % pkg)  # the control: importing does run it
    generated_srv = importlib.import_module("%s.srv" % pkg)
    assert marker.read_text() == "imported"
    real = generated.Thing
    assert thing._md5sum == real._md5sum and thing._type == real._type
    assert thing._full_text == real._full_text
    assert (thing.__slots__, thing._slot_types) == (real.__slots__, real._slot_types)
    assert (thing.SMALL, thing.BYTE, thing.RATIO, thing.YES, thing.GREETING, thing.EMPTY) == \
        (real.SMALL, real.BYTE, real.RATIO, real.YES, real.GREETING, real.EMPTY)
    assert ask._md5sum == generated_srv.Ask._md5sum and ask._type == generated_srv.Ask._type
    assert ask._request_class._md5sum == generated_srv.AskRequest._md5sum
    assert ask._response_class._md5sum == generated_srv.AskResponse._md5sum

    # The two classes agree on the bytes: what one serialises the other reads.
    sent = thing(count=7, vec=[1.0, 2.0, 3.0], words=["a", "b"])
    sent.point.x = 2.5
    sent.others = [type(sent.pair[0])(name="n", value=-4)]
    buff = io.BytesIO()
    sent.serialize(buff)
    got = real().deserialize(buff.getvalue())
    assert (got.count, list(got.vec), got.words, got.point.x, got.others[0].name, got.others[0].value) == \
        (7, [1.0, 2.0, 3.0], ["a", "b"], 2.5, "n", -4)


def test_built_check_and_missing_definitions(student_package, tmp_path):
    pkg, marker = student_package
    with pytest.raises(messages.NotBuilt, match="not built"):
        messages.message_class("%s/Unbuilt" % pkg)
    os.remove(tmp_path / "src" / pkg / "msg" / "Other.msg")  # built, but a definition it uses is gone
    with pytest.raises(messages.InterfaceError, match="%s/Other" % pkg):
        messages.message_class("%s/Thing" % pkg)
    assert not marker.exists()


def test_a_same_named_package_built_elsewhere_never_stands_in(student_package, tmp_path, monkeypatch):
    """The student's overlay holds `pkg` with Thing.msg but never generated it (no
    add_message_files); another workspace (the reference) built a package of the same name, and
    its module is what `import pkg.msg` would find first. Judged by path: not built."""
    pkg, marker = student_package
    overlay = tmp_path / "overlay"
    (overlay / "src").mkdir(parents=True)
    shutil.copytree(tmp_path / "src" / pkg, overlay / "src" / pkg)
    (overlay / "devel" / "lib" / "python3" / "dist-packages" / pkg).mkdir(parents=True)
    (overlay / "devel" / ".catkin").write_text(str(overlay / "src"))
    monkeypatch.setenv("ROS_PACKAGE_PATH", "%s:%s" % (overlay / "src", os.environ["ROS_PACKAGE_PATH"]))
    monkeypatch.setenv("CMAKE_PREFIX_PATH", "%s:%s" % (overlay / "devel", os.environ["CMAKE_PREFIX_PATH"]))
    messages.forget()
    assert messages.built_space(pkg) == str(overlay / "devel")
    assert importlib.util.find_spec(pkg) is not None  # the other workspace's module is importable
    with pytest.raises(messages.NotBuilt, match="no generated Python module %s/msg/_Thing.py in %s"
                       % (pkg, overlay / "devel")):
        messages.message_class("%s/Thing" % pkg)
    (overlay / "devel" / ".catkin").unlink()  # a package folder no workspace on the path built
    messages.forget()
    with pytest.raises(messages.NotBuilt, match="no workspace on the path built package %s" % pkg):
        messages.message_class("%s/Thing" % pkg)
    assert not marker.exists()


@pytest.mark.parametrize("msg_type", ["geometry_msgs/PoseStamped", "std_msgs/Header", "sensor_msgs/Image",
                                      "actionlib_msgs/GoalStatusArray", "turtlesim/Pose"])
def test_system_message_from_its_files_matches_the_generated_class(msg_type):
    pkg, base = msg_type.split("/")
    real = getattr(importlib.import_module(pkg + ".msg"), base)
    built = messages.message_class_from_text(msg_type, messages.definition_text(msg_type), messages.definition_text)
    assert (built._md5sum, built._full_text, built.__slots__, built._slot_types) == \
        (real._md5sum, real._full_text, real.__slots__, real._slot_types)
    assert built.__module__ != real.__module__


@pytest.mark.parametrize("srv_type", ["turtlesim/Spawn", "std_srvs/Trigger", "turtlesim/TeleportAbsolute"])
def test_system_service_from_its_file_matches_the_generated_class(srv_type):
    pkg, base = srv_type.split("/")
    real = getattr(importlib.import_module(pkg + ".srv"), base)
    text = messages.read_definition(messages.definition_path(pkg, base, "srv"), "srv")
    built = messages.service_class_from_text(srv_type, text, messages.definition_text)
    assert (built._type, built._md5sum) == (real._type, real._md5sum)
    assert built._request_class._md5sum == real._request_class._md5sum
    assert built._response_class.__slots__ == real._response_class.__slots__


def test_system_types_are_imported_and_workspace_types_built_from_their_files():
    """A workspace package (the course's turtlesim here) may be shadowed by a student's package of
    the same name, whose Python the check cannot see: its classes come from the files ROS finds."""
    import std_msgs.msg
    import turtlesim.msg
    assert messages.system_package("std_msgs") and not messages.system_package("turtlesim")
    assert messages.message_class("std_msgs/String") is std_msgs.msg.String
    pose = messages.message_class("turtlesim/Pose")
    assert pose is not turtlesim.msg.Pose and pose._md5sum == turtlesim.msg.Pose._md5sum


def test_a_link_to_the_system_package_is_not_the_system_package(tmp_path, monkeypatch):
    """An overlay folder on sys.path whose package is a link to Debian's: the folder is the student's
    (they could swap the link), so the package is read from definitions, not imported."""
    name = next((n for n in ("move_base_msgs", "tf2_msgs", "nav_msgs", "sensor_msgs", "actionlib_msgs")
                 if n not in sys.modules and os.path.isdir("/usr/lib/python3/dist-packages/" + n)), None)
    if name is None:
        pytest.skip("every candidate package is imported already")
    assert messages.imports_safely(name)
    (tmp_path / name).symlink_to("/usr/lib/python3/dist-packages/" + name)
    monkeypatch.syspath_prepend(str(tmp_path))
    importlib.invalidate_caches()
    assert not messages.imports_safely(name)
    assert name not in sys.modules


INJECTIONS = [
    # genmsg checks no constant name: genpy writes `<name> = <value>` into the class body.
    'int32 a\nint32 open(MARK,"w").close();y=1',
    'string open(MARK,"w").close();y=1',
    # A full text ending in a backslash escapes the end of genpy's """ string; a constant with
    # """ in its value then ends it, and the rest of the value is code.
    'string A="""+str(open(MARK,"w").close())#\nint32 a\n# \\',
]


@pytest.mark.parametrize("template", INJECTIONS)
def test_definitions_made_to_run_code_run_nothing(template, tmp_path):
    marker = str(tmp_path / "ran")
    text = template.replace("MARK", repr(marker).replace("'", '"'))
    genpy.dynamic.generate_dynamic("evil/Msg", text)  # the control: genpy alone runs the payload
    assert os.path.exists(marker)
    os.remove(marker)
    try:
        built = messages.message_class_from_text("evil/Msg", text)
    except messages.InterfaceError as err:
        assert "evil/Msg" in str(err)
    else:
        assert built._md5sum == genmsg_md5("evil/Msg", text)
    assert not os.path.exists(marker)


def genmsg_md5(msg_type: str, text: str) -> str:
    context = genmsg.MsgContext.create_default()
    spec = genmsg.msg_loader.load_msg_from_string(context, text, msg_type)
    genmsg.msg_loader.load_msg_depends(context, spec, {})
    return genmsg.compute_md5(context, spec)


@pytest.mark.parametrize("text, words", [
    ("int32", "invalid"),
    ("int32 1x", "invalid"),
    ("int32[][] x", "1-dimensional"),
    ("int32 serialize", "cannot be named serialize"),
    ("int32 a\nint32 a=1", "both a field and a constant"),
    ("float64 X=nan", "not a plain float64"),
    ("float64 X=1e999", "not a plain float64"),
    ("bool B=[1]", "not a plain bool"),
    ("string S=a\\b", "backslash"),
    ("int32[100000000] big", "more than"),
    ("nopkg/Nope x", "nopkg/Nope, whose definition is not found"),
    ("Loop next", "contains itself"),
    ("a b c", "invalid"),
])
def test_malformed_definitions_are_sentences(text, words):
    with pytest.raises(messages.InterfaceError) as err:
        messages.message_class_from_text("pkg/Loop", text)
    assert words in str(err.value)


def test_a_cycle_through_another_type_is_named():
    texts = {"pkg/B": "pkg/C c", "pkg/C": "pkg/B b\nint32 x"}
    with pytest.raises(messages.InterfaceError, match="contains itself"):
        messages.message_class_from_text("pkg/A", "pkg/B b", texts.get)


def test_definition_files_are_read_as_plain_files(tmp_path):
    folder = tmp_path / "msg"
    folder.mkdir()
    (folder / "Real.msg").write_text("int32 a\n")
    assert messages.read_definition(str(folder / "Real.msg")) == "int32 a\n"
    (folder / "Link.msg").symlink_to(folder / "Real.msg")
    with pytest.raises(messages.InterfaceError, match="link"):
        messages.read_definition(str(folder / "Link.msg"))
    os.mkfifo(folder / "Fifo.msg")  # opening a fifo for reading would wait for a writer forever
    with pytest.raises(messages.InterfaceError, match="not a regular file"):
        messages.read_definition(str(folder / "Fifo.msg"))
    (folder / "Big.msg").write_bytes(b"#" * (messages.MAX_DEFINITION_BYTES + 1))
    with pytest.raises(messages.InterfaceError, match="longer than"):
        messages.read_definition(str(folder / "Big.msg"))
    (folder / "Latin.msg").write_bytes(b"# caf\xe9\nint32 a\n")
    with pytest.raises(messages.InterfaceError, match="not UTF-8"):
        messages.read_definition(str(folder / "Latin.msg"))


def check_any_text(text: str, marker: str) -> None:
    """Any text: a class whose md5 is genmsg's, or an InterfaceError that _check raised (not
    genpy failing on something let through), and never a marker written."""
    try:
        built = messages.message_class_from_text("pkg/Fuzz", text.replace("MARK", marker), messages.definition_text)
    except messages.InterfaceError as err:
        assert str(err) and not str(err).startswith("genpy could not"), str(err)
    else:
        if "Header" not in text:  # genmsg_md5 has no search path for std_msgs
            assert built._md5sum == genmsg_md5("pkg/Fuzz", text.replace("MARK", marker))
        built()  # a default message can be made
    assert not os.path.exists(marker)


PIECES = st.sampled_from(["int32", "string", "float64", "bool", "uint8[]", "int8[3]", "time", "Header", "pkg/Fuzz",
                          "x", "X", "self", "class", "serialize", "=", "==", "1", "-1", "1.5e3", "nan", "True",
                          "#", " ", "  ", '"""', "'", '"', "\\", "\r", "\t", "é", "[", "]", "/", ";",
                          'open("MARK","w")', "+", "\x00", "\x0c", "0x10", "1_0"])


TYPES = st.sampled_from(["int32", "string", "float64", "bool", "uint8[]", "int8[3]", "char", "byte", "time",
                         "duration", "Header", "pkg/Fuzz", "Fuzz", "std_msgs/Header", "string[2]", "bool[]"])
CONSTANT_TYPES = st.sampled_from(["int32", "uint8", "int64", "string", "float32", "float64", "bool", "char"])
NAMES = st.one_of(st.sampled_from(["x", "X", "y", "self", "class", "serialize", "_x", "a1", "é", "1a", "x.y"]),
                  st.text(st.characters(min_codepoint=33, max_codepoint=126), min_size=1, max_size=8))
VALUES = st.one_of(st.sampled_from(["1", "-1", "255", "256", "1.5e3", "nan", "inf", "True", "false", '"""', "'",
                                    '"', "\\", "a\\", '"""+str(open("MARK","w").close())#', "0x10", "1_0", ""]),
                   st.text(max_size=12))
LINES = st.one_of(st.builds("{} {}".format, TYPES, NAMES),
                  st.builds("{} {}={}".format, CONSTANT_TYPES, NAMES, VALUES),
                  st.lists(PIECES, max_size=6).map("".join))
COMMENTS = st.one_of(st.just(""), st.builds("  # {}".format, VALUES))


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.lists(st.builds("{}{}".format, LINES, COMMENTS), max_size=8).map("\n".join))
def test_any_definition_of_likely_lines_is_a_class_or_a_sentence(tmp_path, text):
    check_any_text(text, str(tmp_path / "ran"))


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.text(max_size=200))
def test_any_text_is_a_class_or_a_sentence(tmp_path, text):
    check_any_text(text, str(tmp_path / "ran"))


@settings(max_examples=100, deadline=None)
@given(st.text(max_size=120))
def test_any_service_text_is_a_class_or_a_sentence(text):
    try:
        built = messages.service_class_from_text("pkg/Srv", text)
    except messages.InterfaceError as err:
        assert str(err) and not str(err).startswith("genpy could not"), str(err)
    else:
        assert built._request_class._type == "pkg/SrvRequest" and len(built._md5sum) == 32


@pytest.mark.parametrize("name", ["", "std_msgs", "std_msgs/", "/String", "../x/y", "a/b/c", "a b/c", None, 3])
def test_type_names_other_than_pkg_slash_type_are_refused(name):
    with pytest.raises(messages.InterfaceError, match="is not a message type name"):
        messages.message_class(name)
