"""Python's start-up hook in the course environment: rospy without numpy's and pyparsing's cost.

course_env's env hook puts this folder (and nothing else in it) on PYTHONPATH; site.py imports
`usercustomize` at every interpreter start where the user site is enabled (Debian's own
sitecustomize in /etc/python3.11 is left alone). Debian's genpy (genpy/message.py) imports numpy
at module level only to list numpy's scalar types in `_valid_float_types`, which check_type()
reads after a serialisation has already failed, to say why. That import costs every rospy,
roslaunch and rostopic process about 8.7 MiB and 75 ms of CPU.

The finder installed here acts on one import only, genpy.message's, and only when numpy is not
loaded yet: genpy.message's own `import numpy` fails as if numpy were absent (for that statement,
in that thread; numpy stays importable for everyone else and afterwards), and its
`_valid_float_types` becomes a list that also holds numpy's scalar types of upstream's list
whenever numpy is loaded, so check_type() gives upstream's verdict for every value. With numpy
loaded first, or a genpy.message that uses numpy anywhere else, nothing changes. Whatever goes
wrong in here is swallowed: the import then runs as it would without the hook.

Likewise pyparsing: every rospy process imports roslib, which imports catkin_pkg.package, whose
catkin_pkg.condition imports pyparsing at module level (6.5 MiB, 36-48 ms of CPU) for one use:
parsing a package.xml `condition` attribute, which evaluate_condition() does only for a condition
that is not None (almost none has one). A second finder loads catkin_pkg.condition with its own
`import pyparsing` answered by a stand-in (its `__import__` only: pyparsing is neither refused nor
replaced for anyone else); the first attribute asked of the stand-in imports pyparsing and puts it
in the module's globals, in place of the stand-in. See docs/rospy_limits.md.

Likewise ssl (0.8 MiB a process): xmlrpc.client imports http.client, and xml.sax.saxutils (roslaunch,
rosmaster) urllib.request, whose `import ssl` serve only functions (HTTPS). Two more finders of the
second's kind give each of those modules a stand-in for ssl, which imports the real ssl on first
use. Anyone else's `import ssl` is the real one.
"""
import builtins
import sys
from _thread import get_ident

TARGET = "genpy.message"
NUMPY = "numpy"
# Upstream's numpy entries of genpy.message._valid_float_types, in its order.
NUMPY_FLOAT_TYPES = ("float32", "float64", "int8", "int16", "int32", "int64",
                     "uint8", "uint16", "uint32", "uint64")
IMPORT_MACHINERY = ("importlib._bootstrap", __name__)


class FloatTypes(list):
    """genpy.message._valid_float_types as loaded without numpy (float, int, int), which also
    contains numpy's scalar types of upstream's list while numpy is in sys.modules."""

    __slots__ = ()

    def __contains__(self, item: object) -> bool:
        if list.__contains__(self, item):
            return True
        numpy = sys.modules.get(NUMPY)
        if numpy is None:
            return False
        return item in tuple(getattr(numpy, name) for name in NUMPY_FLOAT_TYPES if hasattr(numpy, name))


def numpy_only_builds_the_list(code: object) -> bool:
    """True when a module's code imports numpy and sets _valid_float_types at module level, and no
    function or class in it names numpy or np: then hiding numpy from its module-level import can
    change nothing but that list (genpy.message of Debian's genpy 0.6.16, and upstream's)."""
    if not {NUMPY, "_valid_float_types"} <= set(code.co_names):
        return False
    nested = [c for c in code.co_consts if isinstance(c, type(code))]
    while nested:
        inner = nested.pop()
        if {NUMPY, "np"} & set(inner.co_names):
            return False
        nested.extend(c for c in inner.co_consts if isinstance(c, type(code)))
    return True


def importer_name() -> str:
    """The module whose code runs the import under way in this thread (the first frame outside
    the import machinery and this module)."""
    frame = sys._getframe(1)
    while frame is not None and frame.f_globals.get("__name__") in IMPORT_MACHINERY:
        frame = frame.f_back
    return "" if frame is None or frame.f_code.co_name != "<module>" else frame.f_globals.get("__name__", "")


class DeferringLoader:
    """A module's own loader, whose exec_module runs through its deferral's load()."""

    def __init__(self, loader: object, deferral: "OneModuleDeferral") -> None:
        self.loader = loader
        self.deferral = deferral

    def create_module(self, spec: object) -> object:
        return self.loader.create_module(spec)

    def exec_module(self, module: object) -> None:
        self.deferral.load(module, self.loader)

    def __getattr__(self, name: str) -> object:
        return getattr(self.loader, name)


class OneModuleDeferral:
    """A meta path finder acting on the import of one module (`target`) while `dependency` is
    not loaded: it gives the module's spec as the next finders give it, with a DeferringLoader,
    and leaves sys.meta_path once the module is loaded, or found with `dependency` loaded."""

    target = ""
    dependency = ""

    def __init__(self, meta_path: list, modules: dict) -> None:
        self.meta_path = meta_path
        self.modules = modules

    def find_spec(self, fullname: str, path: object = None, target: object = None) -> object:
        if fullname != self.target:
            return None
        try:
            return self.target_spec(path, target)
        except Exception:
            self.leave()
            return None

    def target_spec(self, path: object, target: object) -> object:
        if self.modules.get(self.dependency) is not None:
            self.leave()
            return None
        for finder in list(self.meta_path):
            find = getattr(finder, "find_spec", None)
            spec = None if finder is self or find is None else find(self.target, path, target)
            if spec is not None:
                break
        else:
            spec = None
        if spec is None or not all(hasattr(spec.loader, m) for m in ("get_code", "exec_module", "create_module")):
            self.leave()
            return None
        spec.loader = DeferringLoader(spec.loader, self)
        return spec

    def load(self, module: object, loader: object) -> None:
        raise NotImplementedError

    def leave(self) -> None:
        try:
            while self in self.meta_path:
                self.meta_path.remove(self)
        except Exception:
            pass

    @classmethod
    def install(cls, meta_path: list, modules: dict) -> None:
        """First on `meta_path`, unless the module or its dependency is loaded already."""
        if cls.target not in modules and modules.get(cls.dependency) is None:
            meta_path.insert(0, cls(meta_path, modules))


class NumpyDeferral(OneModuleDeferral):
    """Sees genpy.message's import, then its `import numpy`."""

    target = TARGET
    dependency = NUMPY

    def __init__(self, meta_path: list, modules: dict) -> None:
        super().__init__(meta_path, modules)
        self.loading_thread = None  # the thread running genpy.message's module code, while it does
        self.refused = False  # genpy.message's `import numpy` failed through us

    def find_spec(self, fullname: str, path: object = None, target: object = None) -> object:
        if fullname == NUMPY and self.refuses_numpy():
            raise ModuleNotFoundError("No module named 'numpy' (deferred: course_env's usercustomize)",
                                      name=NUMPY)
        return super().find_spec(fullname, path, target)

    def refuses_numpy(self) -> bool:
        try:
            if self.loading_thread != get_ident() or importer_name() != TARGET:
                return False
            self.refused = True
            return True
        except Exception:
            return False

    def load(self, module: object, loader: object) -> None:
        """Run genpy.message's code in `module` as `loader` would, its `import numpy` refused when
        that changes nothing but _valid_float_types, which then becomes a FloatTypes."""
        try:
            module.__loader__ = module.__spec__.loader = loader
            code = loader.get_code(module.__name__)
            hide = code is not None and numpy_only_builds_the_list(code)
        except Exception:
            self.leave()
            loader.exec_module(module)
            return
        if not hide:
            self.leave()
            loader.exec_module(module)
            return
        self.loading_thread = get_ident()
        try:
            exec(code, module.__dict__)
        finally:
            self.loading_thread = None
            self.leave()
        if self.refused:
            try:
                module._valid_float_types = FloatTypes(module._valid_float_types)
            except Exception:
                pass


# -- a dependency imported at module level but used only in functions ---------------------------

class LazyFunction:
    """Stands in a module's globals for a function of the deferred dependency until it is loaded."""

    __slots__ = ("standin", "name")

    def __init__(self, standin: "DependencyStandin", name: str) -> None:
        self.standin = standin
        self.name = name

    def __call__(self, *args: object, **kwargs: object) -> object:
        return getattr(self.standin.load(), self.name)(*args, **kwargs)


class DependencyStandin:
    """A module's `import dependency` until it uses it: any attribute asked for imports the
    dependency and puts it, and its functions, in the module's globals where the stand-ins were."""

    def __init__(self, module_globals: dict, modules: dict, dependency: str, functions: tuple) -> None:
        self._globals = module_globals
        self._modules = modules
        self._dependency = dependency
        for name in functions:
            setattr(self, name, LazyFunction(self, name))

    def load(self) -> object:
        real = self._modules.get(self._dependency)
        if real is None:
            real = __import__(self._dependency)
        for key, value in list(self._globals.items()):
            if value is self:
                self._globals[key] = real
            elif isinstance(value, LazyFunction) and value.standin is self:
                self._globals[key] = getattr(real, value.name)
        return real

    def __getattr__(self, name: str) -> object:
        if name.startswith("__"):  # not the dependency's private names: http.client uses ssl's
            raise AttributeError(name)
        return getattr(self.load(), name)


class DependencyDeferral(OneModuleDeferral):
    """Sees `target`'s import; runs its code with a stand-in for `dependency`, and for
    `functions` (what it takes from the dependency by name: `from dependency import name`)."""

    functions: tuple = ()

    def load(self, module: object, loader: object) -> None:
        """Run the target's code in `module` as `loader` would, its `import dependency` answered
        by a stand-in while the dependency is not loaded."""
        try:
            module.__loader__ = module.__spec__.loader = loader
            code = loader.get_code(module.__name__)
            standin = DependencyStandin(module.__dict__, self.modules, self.dependency, self.functions)
            modules, dependency = self.modules, self.dependency
            real_import = builtins.__import__

            def import_(name, globals=None, locals=None, fromlist=(), level=0):
                if name == dependency and level == 0 and modules.get(dependency) is None:
                    return standin
                return real_import(name, globals, locals, fromlist, level)
            module.__dict__["__builtins__"] = dict(builtins.__dict__, __import__=import_)
        except Exception:
            self.leave()
            loader.exec_module(module)
            return
        try:
            exec(code, module.__dict__)
        finally:
            self.leave()


class PyparsingDeferral(DependencyDeferral):
    """catkin_pkg.condition's pyparsing. What it takes from pyparsing by name at module level
    (`from pyparsing import infixNotation`; operatorPrecedence before pyparsing 1.5.7) are
    functions it only calls, later."""

    target = "catkin_pkg.condition"
    dependency = "pyparsing"
    functions = ("infixNotation", "operatorPrecedence")


class SslDeferral(DependencyDeferral):
    """http.client's ssl, which it uses only inside HTTPSConnection's methods: every rospy process
    imports http.client (through xmlrpc.client), and none speaks HTTPS to a master."""

    target = "http.client"
    dependency = "ssl"


class UrllibSslDeferral(DependencyDeferral):
    """urllib.request's ssl, used only inside functions (urlopen's cafile, HTTPS's handler):
    roslaunch and rosmaster import it through xml.sax.saxutils."""

    target = "urllib.request"
    dependency = "ssl"


def install(meta_path: list = sys.meta_path, modules: dict = sys.modules) -> None:
    """The finders, each first on `meta_path` unless what it defers is loaded already."""
    for deferral in (NumpyDeferral, PyparsingDeferral, SslDeferral, UrllibSslDeferral):
        try:
            deferral.install(meta_path, modules)
        except Exception:
            pass


install()
