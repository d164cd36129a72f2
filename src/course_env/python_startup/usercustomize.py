"""Python's start-up hook in the course environment: rospy without numpy's cost.

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
See docs/rospy_limits.md.
"""
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


class GenpyMessageLoader:
    """genpy.message's own loader, whose exec_module runs through NumpyDeferral.load."""

    def __init__(self, loader: object, deferral: "NumpyDeferral") -> None:
        self.loader = loader
        self.deferral = deferral

    def create_module(self, spec: object) -> object:
        return self.loader.create_module(spec)

    def exec_module(self, module: object) -> None:
        self.deferral.load(module, self.loader)

    def __getattr__(self, name: str) -> object:
        return getattr(self.loader, name)


class NumpyDeferral:
    """The meta path finder: sees genpy.message's import, then its `import numpy`; leaves
    sys.meta_path once genpy.message is loaded or found with numpy already loaded."""

    def __init__(self, meta_path: list, modules: dict) -> None:
        self.meta_path = meta_path
        self.modules = modules
        self.loading_thread = None  # the thread running genpy.message's module code, while it does
        self.refused = False  # genpy.message's `import numpy` failed through us

    def find_spec(self, fullname: str, path: object = None, target: object = None) -> object:
        if fullname == NUMPY and self.refuses_numpy():
            raise ModuleNotFoundError("No module named 'numpy' (deferred: course_env's usercustomize)",
                                      name=NUMPY)
        if fullname != TARGET:
            return None
        try:
            return self.genpy_message_spec(path, target)
        except Exception:
            self.leave()
            return None

    def refuses_numpy(self) -> bool:
        try:
            if self.loading_thread != get_ident() or importer_name() != TARGET:
                return False
            self.refused = True
            return True
        except Exception:
            return False

    def genpy_message_spec(self, path: object, target: object) -> object:
        """genpy.message's spec as the next finders give it, with our loader; None (and this
        finder gone) when numpy is loaded already or the spec is not one we know."""
        if self.modules.get(NUMPY) is not None:
            self.leave()
            return None
        for finder in list(self.meta_path):
            find = getattr(finder, "find_spec", None)
            spec = None if finder is self or find is None else find(TARGET, path, target)
            if spec is not None:
                break
        else:
            spec = None
        if spec is None or not all(hasattr(spec.loader, m) for m in ("get_code", "exec_module", "create_module")):
            self.leave()
            return None
        spec.loader = GenpyMessageLoader(spec.loader, self)
        return spec

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

    def leave(self) -> None:
        try:
            while self in self.meta_path:
                self.meta_path.remove(self)
        except Exception:
            pass


def install(meta_path: list = sys.meta_path, modules: dict = sys.modules) -> None:
    """Put the finder first on `meta_path`, unless genpy.message or numpy is loaded already."""
    if TARGET in modules or modules.get(NUMPY) is not None:
        return
    meta_path.insert(0, NumpyDeferral(meta_path, modules))


try:
    install()
except Exception:
    pass
