"""JUnit XML as rostest and rosunit write it: counts and the check's own message."""
from course_checks import junit

TRACE = '''  File "/usr/lib/python3.11/unittest/case.py", line 57, in testPartExecutor
    yield
  File "/x/check.py", line 28, in test_pub_and_sub
    self.assertTrue(wait_for(printed, 20), "the subscriber printed none of the messages")
'''

ROSUNIT = '''<?xml version="1.0" encoding="utf-8"?>
<testsuite errors="1" failures="1" name="unittest.suite.TestSuite" tests="3" time="0.001">
<testcase classname="__main__.T" name="test_a" time="0.0003"><error type="RuntimeError">boom here
%(trace)s</error></testcase>
<testcase classname="__main__.T" name="test_b" time="0.0001"><failure type="AssertionError">\
False is not true : no executable in package chatter publishes /chatter_talk
(found: a.py, b.py)
%(trace)s</failure></testcase>
<testcase classname="__main__.T" name="test_c" time="0.0001"/>
</testsuite>''' % {"trace": TRACE}

LAUNCHER_OK = '''<?xml version="1.0" encoding="utf-8"?>
<testsuite errors="0" failures="0" name="unittest.suite.TestSuite" tests="1" time="1.1">
<testcase classname="rostest.runner.RosTest" name="testerr" time="1.1"/>
<system-out>&lt;![CDATA[ lots of launch text ]]&gt;</system-out></testsuite>'''

LAUNCHER_TIMEOUT = '''<?xml version="1.0" encoding="utf-8"?>
<testsuite errors="1" failures="0" name="unittest.suite.TestSuite" tests="1" time="5.8">
<testcase classname="rostest.runner.RosTest" name="testtl" time="5.8"><error type="RLTestTimeoutException">\
max time [5.0s] allotted for test [tl] of type [chatter/example_pub.py]
%s</error></testcase></testsuite>''' % TRACE

LAUNCHER_NO_RESULTS = '''<testsuite errors="0" failures="1" tests="1"><testcase classname="rostest.runner.RosTest"
name="testcrash" time="0.2"><failure type="AssertionError">\
False is not true : test [crash] did not generate test results
%s</failure></testcase></testsuite>''' % TRACE


def test_assertion_message_without_traceback_or_prefix():
    suite = junit.parse_text(ROSUNIT)
    assert suite.tests == 3
    assert [(c.name, c.problem) for c in suite.failed] == [("test_a", "error"), ("test_b", "failure")]
    assert suite.failed[1].message == ("no executable in package chatter publishes /chatter_talk\n"
                                       "(found: a.py, b.py)")


def test_an_exception_in_the_check_keeps_its_type():
    assert junit.parse_text(ROSUNIT).failed[0].message == "RuntimeError: boom here"


def test_rostest_time_limit_and_missing_results_in_words():
    timeout = junit.parse_text(LAUNCHER_TIMEOUT).failed[0].message
    assert timeout == "the check [tl] did not finish within its time limit of 5.0 s"
    crash = junit.parse_text(LAUNCHER_NO_RESULTS).failed[0].message
    assert "ended without reporting results" in crash and "[crash]" in crash


def test_combine_counts_the_checks_tests_and_every_failure():
    tests, failures = junit.combine(junit.parse_text(LAUNCHER_OK), [junit.parse_text(ROSUNIT)])
    assert tests == 3
    assert [name for name, _ in failures] == ["test_a", "test_b"]
    tests, failures = junit.combine(junit.parse_text(LAUNCHER_NO_RESULTS), [])
    assert tests == 1 and failures[0][0] == "testcrash"


def test_testsuites_root_and_unparsable_file(tmp_path):
    wrapped = "<testsuites>%s</testsuites>" % ROSUNIT.split("?>", 1)[1]
    assert junit.parse_text(wrapped).tests == 3
    bad = tmp_path / "bad.xml"
    bad.write_text("<testsuite")
    assert junit.parse_file(str(bad)) is None


def test_write_then_read_back(tmp_path):
    path = str(tmp_path / "out.xml")
    cases = [junit.Case("chatter", "student1", 2.5, None, ""),
             junit.Case("checkpoint1", "student1", 1.0, "failure", "no package named my_chatter\nfound: mychatter")]
    junit.write(path, "student1", cases)
    suite = junit.parse_file(path)
    assert suite.tests == 2
    assert suite.failed[0].message == "no package named my_chatter\nfound: mychatter"


def test_unittest_wording_of_any_assertion_goes():
    """`None is not true : `, `[] is not true : `, `1 != 2 : `, `unexpectedly None : ` (a check
    that left longMessage on): the student reads the check's sentence alone."""
    sentence = "no node of the launch file publishes /turtle1/cmd_vel: add the teleop node"
    for prefix in ("None is not true : ", "[] is not true : ", "0 is not true : ", "True is not false : ",
                   "{'a': [1, 2]} is not true : ", "1 != 2 : ", "'x' != 'y' : ", "unexpectedly None : "):
        assert junit.clean_message(prefix + sentence + "\n" + TRACE) == sentence, prefix
    assert junit.clean_message(sentence) == sentence
    kept = "the turtle is not where it was : it moved 2 m"  # a check's own colon stays
    assert junit.clean_message(kept) == kept
