"""rostest_main runs the rostest script it is given as __main__, with its own arguments, once
quick_exit is installed (the script stands in for /usr/bin/rostest; no master needed)."""
import json
import subprocess
import sys

import pytest
import rosgraph.xmlrpc

from course_rospy import quick_exit, rostest_main

SCRIPT = '''\
import json, sys
import rosgraph.xmlrpc
print(json.dumps({"name": __name__, "argv": sys.argv,
                  "quick_exit": rosgraph.xmlrpc.XmlRpcNode.shutdown.__name__}))
sys.exit(3)
'''


@pytest.fixture
def original():
    yield
    rosgraph.xmlrpc.XmlRpcNode.shutdown = quick_exit._original_shutdown


def test_the_script_runs_as_main_with_its_arguments_and_quick_exit(tmp_path, capsys, original):
    script = tmp_path / "rostest"
    script.write_text(SCRIPT)
    with pytest.raises(SystemExit) as ended:
        rostest_main.main(["rostest_main", str(script), "pkg", "a.test", "x:=1"])
    assert ended.value.code == 3  # the script's own exit code
    said = json.loads(capsys.readouterr().out)
    assert said == {"name": "__main__", "argv": [str(script), "pkg", "a.test", "x:=1"],
                    "quick_exit": quick_exit._shutdown.__name__}


def test_run_as_a_module_it_exits_with_the_script_exit_code(tmp_path):
    script = tmp_path / "rostest"
    script.write_text(SCRIPT)
    run = subprocess.run([sys.executable, "-P", "-m", "course_rospy.rostest_main", str(script), "--text"],
                         stdout=subprocess.PIPE, text=True, cwd=str(tmp_path), timeout=60)
    assert run.returncode == 3
    assert json.loads(run.stdout)["argv"] == [str(script), "--text"]
