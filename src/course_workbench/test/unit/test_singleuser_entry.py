"""Under a hub the workbench runs jupyterhub-singleuser through venv/singleuser.py, which loads
the hub's database layer (SQLAlchemy, jupyterhub.orm, alembic: 28 MiB in every student's
container) only when something uses it; then the real ones answer, for the hub's modules and for
everyone else."""
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


def in_venv(*code: str) -> dict:
    """What `code` (its parts one after another), run by .venv-jupyter's python after the entry
    script's set-up, prints as JSON."""
    prelude = "import json, runpy, sys\nentry = runpy.run_path(%r, run_name='entry')\n" % SCRIPT
    program = prelude + "".join(textwrap.dedent(part) for part in code)
    done = subprocess.run([PYTHON, "-c", program], capture_output=True, text=True,
                          timeout=120, env=dict(os.environ, PYTHONPATH=""))
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_the_hub_s_command_is_the_entry_script_and_without_a_hub_jupyter_lab():
    assert COURSE.jupyter_command(True) == [PYTHON, SCRIPT] and os.path.isfile(SCRIPT)
    assert COURSE.jupyter_command(False) == [os.path.join(COURSE.jupyter_venv, "bin", "jupyter-lab")]


@needs_venv
def test_what_jupyterhub_orm_does_with_alembic_gets_the_real_alembic():
    found = in_venv("""
        entry["Deferral"]().import_entry()
        import jupyterhub.singleuser
        from jupyterhub import orm
        before = "alembic" in sys.modules
        import alembic.config, alembic.script
        print(json.dumps({
            "before": before,
            "config": orm.alembic.config.Config is alembic.config.Config,
            "command": orm.alembic.command.stamp.__module__,
            "scripts": orm.ScriptDirectory.from_config.__func__ is alembic.script.ScriptDirectory.from_config.__func__,
            "real": type(sys.modules["alembic"]).__name__,
        }))
    """)
    assert found == {"before": False, "config": True, "command": "alembic.command", "scripts": True, "real": "module"}


LOADED = """
    TOPS = ("sqlalchemy", "jupyterhub.orm", "jupyterhub.handlers", "alembic")
    def loaded():
        return [top for top in TOPS if top in sys.modules]
    """
# What the single-user server's modules hold in place of the deferred ones: (module, global) ->
# (the module it stands for, the name there or None for the module itself)
SWAPPED = """
    HELD = {
        ("jupyterhub.utils", "SQLAlchemyError"): ("sqlalchemy.exc", "SQLAlchemyError"),
        ("jupyterhub.roles", "func"): ("sqlalchemy", "func"),
        ("jupyterhub.scopes", "sa"): ("sqlalchemy", None),
        ("jupyterhub.scopes", "orm"): ("jupyterhub.orm", None),
        ("jupyterhub.roles", "orm"): ("jupyterhub.orm", None),
        ("jupyterhub.metrics", "orm"): ("jupyterhub.orm", None),
        ("jupyterhub", "orm"): ("jupyterhub.orm", None),
        ("jupyterhub.log", "HealthCheckHandler"): ("jupyterhub.handlers.pages", "HealthCheckHandler"),
    }
    def swapped():
        # each held name: "real" (the real module's object), "stand-in", or "stale" (a stand-in
        # although the real module is loaded)
        found = {}
        for (module, name), (source, attr) in HELD.items():
            value = getattr(sys.modules[module], name)
            real = sys.modules.get(source)
            if real is not None and value is (real if attr is None else getattr(real, attr)):
                found["%s.%s" % (module, name)] = "real"
            else:
                found["%s.%s" % (module, name)] = "stand-in" if real is None else "stale"
        return found
    """
SQLALCHEMY_NAMES = ("jupyterhub.utils.SQLAlchemyError", "jupyterhub.roles.func", "jupyterhub.scopes.sa")
ORM_NAMES = ("jupyterhub.scopes.orm", "jupyterhub.roles.orm", "jupyterhub.metrics.orm", "jupyterhub.orm")
HANDLER_NAMES = ("jupyterhub.log.HealthCheckHandler",)


def held(real=(), stand_in=()) -> dict:
    return dict({name: "real" for name in real}, **{name: "stand-in" for name in stand_in})


@needs_venv
def test_the_single_user_server_loads_without_the_hub_s_database_layer_and_pages():
    found = in_venv(LOADED, SWAPPED, """
        deferral = entry["Deferral"]()
        deferral.import_entry()
        import jupyterhub.singleuser
        stand_ins = sorted(n for n, m in sys.modules.items() if type(m).__name__ == "StandIn")
        print(json.dumps({"loaded": loaded(), "fell back": deferral.fell_back, "stand-ins in sys.modules": stand_ins,
                          "extension": "jupyterhub.singleuser.extension" in sys.modules, "held": swapped()}))
    """)
    assert found == {"loaded": [], "fell back": False, "stand-ins in sys.modules": [], "extension": True,
                     "held": held(stand_in=SQLALCHEMY_NAMES + ORM_NAMES + HANDLER_NAMES)}


@needs_venv
@pytest.mark.parametrize("first_use", [
    "from jupyterhub import scopes; scopes.orm.User",           # a module stand-in
    "import jupyterhub.orm",                                     # somebody else's import of the ORM
    "from jupyterhub.objects import Server; Server()",          # traitlets' Instance(orm.Server)
])
def test_the_first_use_of_the_orm_loads_it_and_sqlalchemy_everywhere_a_stand_in_was(first_use):
    found = in_venv(LOADED, SWAPPED, """
        entry["Deferral"]().import_entry()
        import jupyterhub.singleuser
        %s
        print(json.dumps({"loaded": loaded(), "held": swapped()}))
    """ % first_use)
    assert found == {"loaded": ["sqlalchemy", "jupyterhub.orm"],
                     "held": held(real=SQLALCHEMY_NAMES + ORM_NAMES, stand_in=HANDLER_NAMES)}


@needs_venv
@pytest.mark.parametrize("first_use", [
    "from jupyterhub import roles; roles.func.count",           # a function's Deferred
    "from jupyterhub import scopes; scopes.sa.select",          # the module stand-in
    "import sqlalchemy.exc",                                     # somebody else's import
])
def test_the_first_use_of_sqlalchemy_loads_it_everywhere_and_the_orm_stays_deferred(first_use):
    found = in_venv(LOADED, SWAPPED, """
        entry["Deferral"]().import_entry()
        import jupyterhub.singleuser
        %s
        first = {"loaded": loaded(), "held": swapped()}
        from jupyterhub import scopes
        scopes.orm.Role
        print(json.dumps({"first": first, "then": {"loaded": loaded(), "held": swapped()}}))
    """ % first_use)
    assert found == {
        "first": {"loaded": ["sqlalchemy"], "held": held(real=SQLALCHEMY_NAMES, stand_in=ORM_NAMES + HANDLER_NAMES)},
        "then": {"loaded": ["sqlalchemy", "jupyterhub.orm"],
                 "held": held(real=SQLALCHEMY_NAMES + ORM_NAMES, stand_in=HANDLER_NAMES)}}


@needs_venv
def test_an_import_of_the_hub_s_pages_loads_everything_and_the_log_sees_its_health_check():
    found = in_venv(LOADED, SWAPPED, """
        entry["Deferral"]().import_entry()
        import jupyterhub.singleuser
        from jupyterhub import log
        from jupyterhub.handlers.pages import HealthCheckHandler
        print(json.dumps({"loaded": loaded(), "held": swapped(),
                          "is the log's": log.HealthCheckHandler is HealthCheckHandler}))
    """)
    assert found == {"loaded": ["sqlalchemy", "jupyterhub.orm", "jupyterhub.handlers"],
                     "held": held(real=SQLALCHEMY_NAMES + ORM_NAMES + HANDLER_NAMES), "is the log's": True}


@needs_venv
def test_after_the_swap_the_hub_s_except_clauses_catch_sqlalchemy_s_errors():
    found = in_venv("""
        entry["Deferral"]().import_entry()
        import jupyterhub.singleuser
        from jupyterhub import utils
        from jupyterhub.objects import Server
        caught = []
        try:
            import sqlalchemy.exc
            raise sqlalchemy.exc.OperationalError("SELECT 1", {}, OSError("disk gone"))
        except utils.SQLAlchemyError as error:
            caught.append(type(error).__name__)
        trait = Server.class_traits()["orm_server"]
        Server()
        from jupyterhub import orm
        print(json.dumps({"caught": caught, "trait": trait.klass is orm.Server}))
    """)
    assert found == {"caught": ["OperationalError"], "trait": True}


@needs_venv
def test_a_name_nobody_deferred_means_the_upstream_import():
    found = in_venv(LOADED, """
        deferral = entry["Deferral"](placeholders={})
        deferral.import_entry()
        import jupyterhub.singleuser, jupyterhub.utils, sqlalchemy.exc
        left = sorted(n for n, m in sys.modules.items() if type(m).__name__ == "StandIn")
        print(json.dumps({"fell back": deferral.fell_back, "loaded": loaded(), "left": left,
                          "real error": jupyterhub.utils.SQLAlchemyError is sqlalchemy.exc.SQLAlchemyError,
                          "watching": any(type(f).__name__ == "Watcher" for f in sys.meta_path)}))
    """)
    assert found == {"fell back": True, "loaded": ["sqlalchemy", "jupyterhub.orm", "jupyterhub.handlers"],
                     "left": [], "real error": True, "watching": True}


@needs_venv
def test_with_sqlalchemy_loaded_already_nothing_is_deferred():
    found = in_venv(LOADED, """
        import sqlalchemy
        deferral = entry["Deferral"]()
        deferral.import_entry()
        import jupyterhub.singleuser, jupyterhub.utils, sqlalchemy.exc
        print(json.dumps({"fell back": deferral.fell_back,
                          "real error": jupyterhub.utils.SQLAlchemyError is sqlalchemy.exc.SQLAlchemyError}))
    """)
    assert found == {"fell back": True, "real error": True}


@needs_venv
def test_threads_using_stand_ins_at_once_leave_none_stale():
    found = in_venv(LOADED, SWAPPED, """
        import threading
        entry["Deferral"]().import_entry()
        import jupyterhub.singleuser
        from jupyterhub import roles, scopes, utils
        start = threading.Barrier(3)
        def use(get):
            start.wait()
            get()
        uses = [lambda: scopes.orm.User, lambda: roles.func.count, lambda: __import__("sqlalchemy.exc")]
        threads = [threading.Thread(target=use, args=(get,)) for get in uses]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        print(json.dumps({"loaded": loaded(), "held": swapped()}))
    """)
    assert found == {"loaded": ["sqlalchemy", "jupyterhub.orm"],
                     "held": held(real=SQLALCHEMY_NAMES + ORM_NAMES, stand_in=HANDLER_NAMES)}
