"""roslab runs in every student's container while the lab page is open: it loads what it uses
and not the workbench start-up's rospkg and course_sandbox (2.3 MiB of resident memory), checked
in a fresh interpreter (this one has imported everything long ago)."""
import json
import subprocess
import sys
from pathlib import Path

NODE = Path(__file__).resolve().parents[2] / "nodes" / "roslab"
NOT_NEEDED = ("rospkg", "course_sandbox", "course_workbench.startup")


def test_roslab_starts_without_the_start_up_s_imports():
    code = ("import json, runpy, sys; runpy.run_path(%r); assert 'course_workbench.roslab' in sys.modules; "
            "print(json.dumps([n for n in %r if n in sys.modules]))" % (str(NODE), NOT_NEEDED))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-3000:]
    assert json.loads(done.stdout.strip().splitlines()[-1]) == []


def test_the_start_up_and_roslab_share_one_default_master_and_token_variable():
    from course_workbench import names, roslab, startup
    assert startup.DEFAULT_MASTER_URI is roslab.DEFAULT_MASTER_URI is names.DEFAULT_MASTER_URI
    assert startup.TOKEN_VAR is roslab.TOKEN_VAR is names.TOKEN_VAR
