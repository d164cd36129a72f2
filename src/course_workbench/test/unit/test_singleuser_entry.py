"""Under a hub the workbench runs jupyterhub-singleuser through venv/singleuser.py, whose hub
database layer comes without alembic (10.4 MiB in every student's container) until something
uses it; then the real alembic answers, for jupyterhub.orm and for everyone else."""
from __future__ import annotations

import json
import os
import subprocess
import textwrap

import pytest

from course_workbench import startup

COURSE = startup.Course()
SCRIPT = os.path.join(COURSE.package, "venv", "singleuser.py")
PYTHON = os.path.join(COURSE.jupyter_venv, "bin", "python3")
needs_venv = pytest.mark.skipif(not os.path.isfile(os.path.join(COURSE.jupyter_venv, "bin", "jupyterhub-singleuser")),
                                reason="no .venv-jupyter with jupyterhub (make deps)")


def in_venv(code: str) -> dict:
    """What `code`, run by .venv-jupyter's python after the entry script's set-up, prints as JSON."""
    prelude = "import json, runpy, sys\nentry = runpy.run_path(%r, run_name='entry')\n" % SCRIPT
    done = subprocess.run([PYTHON, "-c", prelude + textwrap.dedent(code)], capture_output=True, text=True,
                          timeout=120, env=dict(os.environ, PYTHONPATH=""))
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_the_hub_s_command_is_the_entry_script_and_without_a_hub_jupyter_lab():
    assert COURSE.jupyter_command(True) == [PYTHON, SCRIPT] and os.path.isfile(SCRIPT)
    assert COURSE.jupyter_command(False) == [os.path.join(COURSE.jupyter_venv, "bin", "jupyter-lab")]


@needs_venv
def test_the_single_user_server_loads_without_alembic():
    found = in_venv("""
        entry["import_orm_without_alembic"]()
        import jupyterhub.singleuser, jupyterhub.orm
        print(json.dumps({"alembic": sorted(m for m in sys.modules if m.split(".")[0] == "alembic"),
                          "singleuser": "jupyterhub.singleuser.extension" in sys.modules}))
    """)
    assert found == {"alembic": [], "singleuser": True}


@needs_venv
def test_what_jupyterhub_orm_does_with_alembic_gets_the_real_alembic():
    found = in_venv("""
        entry["import_orm_without_alembic"]()
        from jupyterhub import orm
        import alembic.config, alembic.script
        print(json.dumps({
            "config": orm.alembic.config.Config is alembic.config.Config,
            "command": orm.alembic.command.stamp.__module__,
            "scripts": orm.ScriptDirectory.from_config.__func__ is alembic.script.ScriptDirectory.from_config.__func__,
            "real": type(sys.modules["alembic"]).__name__,
        }))
    """)
    assert found == {"config": True, "command": "alembic.command", "scripts": True, "real": "module"}


@needs_venv
def test_with_jupyterhub_orm_loaded_already_nothing_is_deferred():
    found = in_venv("""
        import jupyterhub.orm
        entry["import_orm_without_alembic"]()
        print(json.dumps("alembic.command" in sys.modules))
    """)
    assert found is True
