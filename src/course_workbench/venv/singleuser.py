"""jupyterhub-singleuser, with alembic loaded only if something uses it.

Run by .venv-jupyter's python in place of its `jupyterhub-singleuser` script (course_workbench's
start-up, under a hub): standard library only, it imports nothing of the course.

jupyterhub.orm imports alembic at module level (`import alembic.command`, `import alembic.config`,
`from alembic.script import ScriptDirectory`) for the hub's database upgrades, which a single-user
server never runs; the single-user server imports jupyterhub.orm anyway (through jupyterhub.log
and the hub's scopes). alembic brings mako and pygments: 10.4 MiB of resident memory in every
student's container. Here jupyterhub.orm is imported first with each of those statements given
a stand-in; a stand-in asked for anything afterwards imports the real alembic then. alembic
itself is neither refused nor replaced for anyone else: the stand-ins leave sys.modules as soon
as jupyterhub.orm is loaded. Whatever goes wrong in here, the server starts as upstream's script
starts it.
"""
import importlib
import importlib.abc
import importlib.machinery
import re
import sys
import types

DEFERRED = "alembic"
IMPORTER = "jupyterhub.orm"


class Deferred:
    """A name imported from a stand-in (alembic.script.ScriptDirectory): the real one on use."""

    def __init__(self, module: str, name: str) -> None:
        self._where = (module, name)

    def _real(self) -> object:
        module, name = self._where
        return getattr(importlib.import_module(module), name)

    def __getattr__(self, attr: str) -> object:
        return getattr(self._real(), attr)

    def __call__(self, *args: object, **kwargs: object) -> object:
        return self._real()(*args, **kwargs)


class StandIn(types.ModuleType):
    """alembic or one of its submodules, as jupyterhub.orm's import statements get it."""

    loading = True  # while jupyterhub.orm's code runs: names asked for are Deferred

    def __getattr__(self, attr: str) -> object:
        if attr.startswith("__"):
            raise AttributeError(attr)
        if StandIn.loading:
            return Deferred(self.__name__, attr)
        real = importlib.import_module(self.__name__)
        try:
            return getattr(real, attr)
        except AttributeError:
            return importlib.import_module("%s.%s" % (self.__name__, attr))


class StandInFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Answers alembic's imports with stand-ins while it is on sys.meta_path."""

    def find_spec(self, fullname: str, path: object = None, target: object = None) -> object:
        if fullname != DEFERRED and not fullname.startswith(DEFERRED + "."):
            return None
        return importlib.machinery.ModuleSpec(fullname, self, is_package=True)

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        module = StandIn(spec.name)
        module.__path__ = []
        return module

    def exec_module(self, module: types.ModuleType) -> None:
        pass


def import_orm_without_alembic() -> None:
    """Import jupyterhub.orm with stand-ins for alembic; on any failure leave things as if this
    never ran (jupyterhub.orm then imports alembic itself, as upstream)."""
    if DEFERRED in sys.modules or IMPORTER in sys.modules:
        return
    finder = StandInFinder()
    sys.meta_path.insert(0, finder)
    try:
        importlib.import_module(IMPORTER)
    except Exception:
        sys.modules.pop(IMPORTER, None)
    finally:
        sys.meta_path.remove(finder)
        StandIn.loading = False
        for name in [n for n, m in list(sys.modules.items()) if isinstance(m, StandIn)]:
            del sys.modules[name]


def main() -> int:
    import_orm_without_alembic()
    from jupyterhub.singleuser import main as singleuser
    sys.argv[0] = re.sub(r"(-script\.pyw|\.exe)?$", "", sys.argv[0])
    return singleuser()


if __name__ == "__main__":
    sys.exit(main())
