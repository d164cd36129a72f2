"""jupyterhub-singleuser, with the hub's database layer loaded only if something uses it.

Run by .venv-jupyter's python in place of its `jupyterhub-singleuser` script (course_workbench's
start-up, under a hub): standard library only, it imports nothing of the course.

The single-user server imports the hub's database layer and page handlers although it has no
database and serves no hub page: jupyterhub.log (for its request log) imports the hub's page
handlers, and jupyterhub.services.auth (for its OAuth) the hub's scopes; those import
jupyterhub.orm and SQLAlchemy, the handlers also the hub's users, spawners and cryptography, and
jupyterhub.orm imports alembic at module level for the hub's database upgrades. In every
student's container that is 31 MiB of resident memory: SQLAlchemy 16.8 MiB, alembic (with mako
and pygments) 10.4, the handlers 2.4, the ORM's classes 1.5.

So jupyterhub.singleuser is imported here with SQLAlchemy's, jupyterhub.orm's and
jupyterhub.handlers' imports answered by stand-ins, and only for the names in `PLACEHOLDERS` (any
other name asked for, or any failure, and that import is done again as upstream does it):

- `import sqlalchemy as sa` and `from . import orm` get a module stand-in;
- `from sqlalchemy import func` (or inspect) gets a Deferred, which calls or reads the real one;
- `from sqlalchemy.exc import SQLAlchemyError` gets an exception class of its own, which nothing
  raises: nothing can raise SQLAlchemy's errors while SQLAlchemy is not loaded; likewise
  jupyterhub.log's HealthCheckHandler (for an isinstance test) is a class nothing instantiates;
- traitlets' `Instance(orm.Server)` gets the class's name, which traitlets resolves on first use.

The stand-ins leave sys.modules once jupyterhub.singleuser is loaded. From then on a `Watcher` sees
every import of those modules, whoever asks (a stand-in used, traitlets, any other code): when one
has run, the real module, function or class replaces the stand-in in every module's globals, so
`except SQLAlchemyError` catches SQLAlchemy's errors from the moment SQLAlchemy exists. And
jupyterhub.orm's own code always runs with alembic's imports answered by stand-ins that load the
real alembic when used.
"""
import importlib
import importlib.abc
import importlib.machinery
import re
import sys
import threading
import types
from typing import Callable, Dict, List, Optional, Set, Tuple

ALEMBIC = "alembic"
ORM = "jupyterhub.orm"
ENTRY = "jupyterhub.singleuser"
DEFERRED = ("sqlalchemy", ORM, "jupyterhub.handlers")
# (module, name) -> what jupyterhub.singleuser's modules get for `from module import name`:
# "call" a Deferred (a function they call later), "error" an exception class nothing raises,
# "name" the dotted name (traitlets' Instance takes a class or its name)
PLACEHOLDERS: Dict[Tuple[str, str], str] = {
    ("sqlalchemy", "func"): "call",
    ("sqlalchemy", "inspect"): "call",
    ("sqlalchemy.exc", "SQLAlchemyError"): "error",
    (ORM, "Server"): "name",
    ("jupyterhub.handlers.pages", "HealthCheckHandler"): "class",
}


def _within(name: str, top: str) -> bool:
    return name == top or name.startswith(top + ".")


class Unexpected(ImportError):
    """A stand-in was asked for a name that is not in PLACEHOLDERS."""


class Deferred:
    """A name imported from a stand-in (sqlalchemy.func, alembic.script.ScriptDirectory): the
    real one on use."""

    def __init__(self, module: str, name: str) -> None:
        self._where = (module, name)

    def _real(self) -> object:
        module, name = self._where
        return getattr(importlib.import_module(module), name)

    def __getattr__(self, attr: str) -> object:
        if attr.startswith("__"):
            raise AttributeError(attr)
        return getattr(self._real(), attr)

    def __call__(self, *args: object, **kwargs: object) -> object:
        return self._real()(*args, **kwargs)


class StandIn(types.ModuleType):
    """A deferred module as its importers get it. While they load (`_names` set), a name asked
    for is its placeholder; afterwards any name asked for is the real module's."""

    def __init__(self, name: str, names: Optional[Callable[[str, str], object]]) -> None:
        super().__init__(name)
        self.__path__ = []
        self._names = names

    def __getattr__(self, attr: str) -> object:
        if attr.startswith("__") or attr == "_names":
            raise AttributeError(attr)
        if self._names is not None:
            return self._names(self.__name__, attr)
        real = importlib.import_module(self.__name__)
        try:
            return getattr(real, attr)
        except AttributeError:
            return importlib.import_module("%s.%s" % (self.__name__, attr))


class StandInFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Answers the imports of `tops` and their submodules with stand-ins while on sys.meta_path."""

    def __init__(self, tops: Tuple[str, ...], names: Optional[Callable[[str, str], object]]) -> None:
        self.tops, self.names = tops, names
        self.made: List[StandIn] = []

    def find_spec(self, fullname: str, path: object = None, target: object = None) -> object:
        if not any(_within(fullname, top) for top in self.tops):
            return None
        return importlib.machinery.ModuleSpec(fullname, self, is_package=True)

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        module = StandIn(spec.name, self.names)
        self.made.append(module)
        return module

    def exec_module(self, module: types.ModuleType) -> None:
        pass

    def __enter__(self) -> "StandInFinder":
        sys.meta_path.insert(0, self)
        return self

    def __exit__(self, *_: object) -> None:
        sys.meta_path.remove(self)
        for module in self.made:
            module._names = None  # from now on, a name asked for is the real module's
            if sys.modules.get(module.__name__) is module:
                del sys.modules[module.__name__]


class Deferral:
    """jupyterhub.singleuser imported with DEFERRED answered by stand-ins, which stay until the
    real modules are imported."""

    def __init__(self, entry: str = ENTRY, tops: Tuple[str, ...] = DEFERRED,
                 placeholders: Optional[Dict[Tuple[str, str], str]] = None) -> None:
        self.entry, self.tops = entry, tops
        self.placeholders = PLACEHOLDERS if placeholders is None else placeholders
        self.given: Dict[Tuple[str, str], object] = {}
        self.stood_in: Set[str] = set()  # the modules some stand-in was made for
        self.fell_back = False
        self.lock = threading.Lock()

    def placeholder(self, module: str, name: str) -> object:
        """What a module gets for `from module import name` while `entry` loads."""
        key = (module, name)
        if key not in self.given:
            kind = self.placeholders.get(key)
            if kind == "call":
                self.given[key] = Deferred(module, name)
            elif kind in ("error", "class"):
                bases = (Exception,) if kind == "error" else ()
                self.given[key] = type(name, bases, {"__module__": __name__})
            elif kind == "name":
                self.given[key] = "%s.%s" % key
            else:
                raise Unexpected("%s.%s is not deferred" % key)
        return self.given[key]

    def import_entry(self) -> None:
        """Import `entry` with stand-ins; on any failure forget every module that import loaded,
        so that the next import of `entry` runs as upstream's. A Watcher stays either way."""
        if any(top in sys.modules for top in self.tops) or self.entry in sys.modules:
            self.fell_back = True
            return
        before = set(sys.modules)
        try:
            with StandInFinder(self.tops, self.placeholder) as finder:
                importlib.import_module(self.entry)
            self.stood_in = {module.__name__ for module in finder.made}
        except Exception:
            for name in set(sys.modules) - before:
                del sys.modules[name]
            self.given.clear()
            self.fell_back = True
        sys.meta_path.insert(0, Watcher(self))

    def swap(self, loaded: str) -> None:
        """Module `loaded` has just run: put it, and what was deferred from it, in place of the
        stand-ins in every module's globals. Only for a module some stand-in was made for (not
        for each of SQLAlchemy's other submodules); no import happens here (no import lock is
        taken while ours is held)."""
        real = sys.modules.get(loaded)
        if real is None or loaded not in self.stood_in:
            return
        swaps = {id(given): (given, getattr(real, name)) for (module, name), given in self.given.items()
                 if module == loaded and self.placeholders[(module, name)] != "name" and hasattr(real, name)}
        with self.lock:
            for module in list(sys.modules.values()):
                namespace = getattr(module, "__dict__", None)
                if not isinstance(namespace, dict) or module is real:
                    continue
                for key, value in list(namespace.items()):
                    pair = swaps.get(id(value))
                    if isinstance(value, StandIn) and value.__name__ == loaded:
                        namespace[key] = real
                    elif pair is not None and value is pair[0]:
                        namespace[key] = pair[1]


class Watcher(importlib.abc.MetaPathFinder):
    """Sees the imports of DEFERRED's modules once `entry` is loaded, whoever asks: each runs as it
    would (jupyterhub.orm's with alembic's imports answered by stand-ins), then Deferral.swap."""

    def __init__(self, deferral: Deferral) -> None:
        self.deferral = deferral

    def find_spec(self, fullname: str, path: object = None, target: object = None) -> object:
        if not any(_within(fullname, top) for top in self.deferral.tops):
            return None
        for finder in list(sys.meta_path):
            find = getattr(finder, "find_spec", None)
            spec = None if finder is self or find is None else find(fullname, path, target)
            if spec is not None:
                break
        else:
            return None
        if not all(hasattr(spec.loader, m) for m in ("create_module", "exec_module")):
            return spec
        spec.loader = ThenSwap(spec.loader, self.deferral, without_alembic=fullname == ORM)
        return spec


class ThenSwap:
    """A module's own loader; its exec_module is followed by Deferral.swap."""

    def __init__(self, loader: object, deferral: Deferral, without_alembic: bool) -> None:
        self.loader, self.deferral, self.without_alembic = loader, deferral, without_alembic

    def create_module(self, spec: object) -> object:
        return self.loader.create_module(spec)

    def exec_module(self, module: types.ModuleType) -> None:
        module.__loader__ = module.__spec__.loader = self.loader
        if self.without_alembic and ALEMBIC not in sys.modules:
            exec_without_alembic(self.loader, module)
        else:
            self.loader.exec_module(module)
        self.deferral.swap(module.__name__)

    def __getattr__(self, name: str) -> object:
        return getattr(self.loader, name)


def exec_without_alembic(loader: object, module: types.ModuleType) -> None:
    """Run jupyterhub.orm's code with alembic's imports answered by stand-ins; should that fail,
    run it again as upstream does."""
    try:
        with StandInFinder((ALEMBIC,), Deferred):  # `from alembic... import name`: a Deferred
            loader.exec_module(module)
    except Exception:
        loader.exec_module(module)


def main() -> int:
    Deferral().import_entry()
    from jupyterhub.singleuser import main as singleuser
    sys.argv[0] = re.sub(r"(-script\.pyw|\.exe)?$", "", sys.argv[0])
    return singleuser()


if __name__ == "__main__":
    sys.exit(main())
