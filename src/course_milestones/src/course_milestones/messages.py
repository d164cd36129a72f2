"""Message and service classes for the checks, built without running any of the student's code.

A check is trusted: it runs with the grader's rights, outside the students' sandbox. The usual
way to get a class (roslib.message.get_message_class, rosservice.get_service_class_by_name)
imports the student's generated Python package, and importing `my_chatter.msg` first runs
`my_chatter/__init__.py`, which a package with catkin_python_setup() fills with whatever it
likes (catkin's devel-space shim execs it). So here:

- a type of the course's or the system's own packages (std_msgs, turtlesim, ...) is imported as
  usual, but only when `import <pkg>` would load it from the system's Python folders or the course
  workspace's own (found without importing anything: an overlay that shadows a package is seen);
- any other type is built from its definition files (`<pkg>/msg/<Type>.msg`, `srv/<Type>.srv`,
  found with rospkg as rosmsg finds them, action messages in devel/share included):
  genmsg parses them and computes the md5 and the full text, genpy generates the class. It
  counts as built only when the space that built that very package (built_space: found by path
  from the package's folder) holds its generated module; a module of the same name that an
  import would find first, from another workspace, never stands in for it.

The definitions are the student's, so they are data to check before genpy turns them into code:
genpy pastes names and constant values into Python source (genmsg does not even check a
constant's name, so the line `int32 open("f","w");x=1` opens a file when the class is made), and
genmsg evaluates nothing but accepts more than genpy can compile. The class is therefore generated from a canonical text
rebuilt from the parsed, checked fields and constants (no comments, same md5), and the original
full text is put back on it afterwards as plain data. Anything else is an InterfaceError whose
message is a sentence for the student; a check never crashes on a definition.
"""
from __future__ import annotations

import glob
import importlib
import importlib.util
import math
import os
import re
import site
import stat
import sys
import sysconfig
import threading
from functools import lru_cache
from typing import Callable, Dict, List, Optional, Sequence, Set, Tuple

import genmsg
import genmsg.msg_loader
import genmsg.msgs
import genpy.dynamic
import rospkg

# Limits on what a definition may make us do (a class is built in the check's own process).
MAX_DEFINITION_BYTES = 64 * 1024      # one .msg/.srv file
MAX_TYPES = 64                        # message types in one definition tree
MAX_DEFAULT_ELEMENTS = 1_000_000      # values a default-constructed message holds (fixed-size arrays)

TYPE_NAME = re.compile(r"^([A-Za-z][A-Za-z0-9_]*)/([A-Za-z][A-Za-z0-9_]*)$")
_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")
_FIELD_TYPE = re.compile(r"^(?:[A-Za-z][A-Za-z0-9_]*/)?[A-Za-z][A-Za-z0-9_]*(?:\[([0-9]*)\])?$")
_INT = re.compile(r"^[+-]?[0-9]+$")
_FLOAT = re.compile(r"^[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?$")
_BOOL = re.compile(r"^(?:True|False|[+-]?[0-9]+)$")
_CONTROL = re.compile(r"[\x00-\x1f\x7f]")
# Names genpy defines in a message class's body: a field (a slot) of that name cannot be created.
_CLASS_BODY_NAMES = frozenset({"serialize", "deserialize", "serialize_numpy", "deserialize_numpy"})
# Where the system's ROS lives when it is not Debian's (/usr): root's, never a student's.
_SYSTEM_ROS_ROOTS = ("/opt/ros",)

FindDefinition = Callable[[str], Optional[str]]


class InterfaceError(Exception):
    """Why a message or service class cannot be had, as a sentence for the student; `cause`, the
    course_format.causes key of a check that fails with it."""
    cause = "not_generated"


class NotBuilt(InterfaceError):
    """The type has no generated Python module: the package does not build it (or is not built)."""


class NoService(InterfaceError):
    """The service is not offered, or its type cannot be read from the master and its server."""
    cause = "no_service"


# -- the public entry points -----------------------------------------------------------------------

_lock = threading.RLock()
_classes: Dict[Tuple[str, str], type] = {}


def message_class(msg_type: str) -> type:
    """The class of message type `pkg/Type`; never imports a student's module (see the module's
    docstring). Raises InterfaceError (NotBuilt when the type has no generated module)."""
    return _cached("msg", msg_type)


def service_class(srv_type: str) -> type:
    """The class of service type `pkg/Type` (with _type, _md5sum, _request_class, _response_class),
    as message_class does it. Raises InterfaceError."""
    return _cached("srv", srv_type)


def service_class_by_name(service: str) -> type:
    """The class of the service `service` offers now: its type comes from the master and the
    service's own connection header (rosservice reads it: data only), its class from service_class."""
    import rosservice  # only here: the rest of the module needs no master
    try:
        srv_type = rosservice.get_service_type(service)
    except Exception as err:  # noqa: BLE001 - the master, the socket, or the server's own header
        raise NoService("cannot read the type of %s: %s" % (service, err)) from None
    if not srv_type:
        raise NoService("no service %s is offered" % service)
    return service_class(srv_type)


def forget() -> None:
    """Drop every cached class and the package index (a test that makes packages calls it)."""
    with _lock:
        _classes.clear()
        _rospack.cache_clear()
        built_space.cache_clear()
        _trusted_roots.cache_clear()


def _cached(kind: str, type_name: str) -> type:
    pkg, base = _split(type_name, kind)
    with _lock:
        key = (kind, type_name)
        if key not in _classes:
            if system_package(pkg) and imports_safely(pkg):
                _classes[key] = _imported(kind, pkg, base)
            else:
                _classes[key] = _from_files(kind, pkg, base)
        return _classes[key]


def _split(type_name: str, kind: str) -> Tuple[str, str]:
    match = TYPE_NAME.match(type_name) if isinstance(type_name, str) else None
    if match is None:
        raise InterfaceError("%r is not a %s type name (package/Type)"
                             % (type_name, "message" if kind == "msg" else "service"))
    return match.group(1), match.group(2)


# -- which packages may be imported ----------------------------------------------------------------

@lru_cache(maxsize=None)
def _trusted_roots() -> Tuple[str, ...]:
    """Folders whose Python is the system's or the course's: the interpreter's own and its site
    folders (Debian's ROS is in /usr/lib/python3/dist-packages), and the Python folder of the
    workspace this module comes from (the course's devel or install space)."""
    roots: Set[str] = set(_SYSTEM_ROS_ROOTS)
    roots.update(site.getsitepackages())
    paths = sysconfig.get_paths()
    roots.update(paths[k] for k in ("stdlib", "platstdlib", "purelib", "platlib") if k in paths)
    own = sys.modules[__name__.split(".")[0]].__spec__
    if own is not None and own.origin:
        roots.add(os.path.dirname(os.path.dirname(own.origin)))  # <site>/course_milestones/__init__.py
    return tuple(sorted(r for r in roots if r and os.path.isabs(r)))


def _under(path: str, roots: Sequence[str]) -> bool:
    path = os.path.normpath(path)
    return any(path == r or path.startswith(r.rstrip("/") + "/") for r in roots)


def trusted_path(path: str) -> bool:
    """Whether `path`, both as written and once its links are resolved, is in a trusted root
    (as written: a link in a student's folder to the system's is still the student's folder)."""
    roots = _trusted_roots()
    real_roots = tuple(os.path.realpath(r) for r in roots)
    return os.path.isabs(path) and _under(path, roots) and _under(os.path.realpath(path), real_roots)


def system_package(pkg: str) -> bool:
    """Whether the package ROS finds for `pkg` is the system's (Debian's /usr/share, /opt/ros),
    not a workspace's. A package of the course workspace may be shadowed by the student's
    overlay of the same name (turtle_patrol, my_chatter): its Python module would still be the
    course's (the check has no overlay on its Python path), so its classes come from the files
    ROS finds, the student's."""
    try:
        path = os.path.realpath(_rospack().get_path(pkg))
    except (rospkg.ResourceNotFound, OSError):
        return False
    return _under(path, ("/usr/share",) + _SYSTEM_ROS_ROOTS)


def imports_safely(pkg: str) -> bool:
    """Whether `import pkg` would run only the course's or the system's code: the module Python
    would load (or has loaded) for `pkg` is in a trusted root. Nothing is imported to find out:
    importlib.util.find_spec of a top-level name only looks at the folders of sys.path."""
    if not _NAME.match(pkg):
        return False
    try:
        module = sys.modules.get(pkg)
        spec = getattr(module, "__spec__", None) if module is not None else importlib.util.find_spec(pkg)
    except (ImportError, ValueError):
        return False
    if spec is None:
        return False
    # Where Python found it on sys.path; an imported package's later __path__ is its own doing.
    places = list(spec.submodule_search_locations or [])
    if spec.origin is not None and spec.has_location:
        places.append(spec.origin)
    elif spec.origin is not None:
        return False  # built-in or frozen: no message package is either
    return bool(places) and all(isinstance(p, str) and trusted_path(p) for p in places)


def _imported(kind: str, pkg: str, base: str) -> type:
    """The class from the package's generated module (trusted: see imports_safely)."""
    try:
        module = importlib.import_module("%s.%s" % (pkg, kind))
        cls = getattr(module, base)
    except (ImportError, AttributeError):
        raise NotBuilt("%s/%s is not built (no generated Python class %s.%s.%s)" % (pkg, base, pkg, kind, base)) \
            from None
    if not isinstance(cls, type) or getattr(cls, "_type", None) != "%s/%s" % (pkg, base):
        raise NotBuilt("%s.%s.%s is not the generated class of %s/%s" % (pkg, kind, base, pkg, base))
    return cls


# -- where a student's definitions are --------------------------------------------------------------

@lru_cache(maxsize=1)
def _rospack() -> rospkg.RosPack:
    return rospkg.RosPack()


@lru_cache(maxsize=None)
def built_space(pkg: str) -> Optional[str]:
    """The devel (or install) space that built the package ROS finds for `pkg`, found by path: the
    first CMAKE_PREFIX_PATH entry with a catkin marker whose source folders (devel/.catkin) hold
    the package's folder, or that holds it itself (an install space's share/<pkg>). None when no
    workspace on the path built that package: it is a folder on ROS_PACKAGE_PATH, not built.
    This, and never the module an import would find first, is where its generated code must be:
    a package of the same name elsewhere (another workspace) cannot stand in for it."""
    try:
        folder = os.path.realpath(_rospack().get_path(pkg))
    except (rospkg.ResourceNotFound, OSError):
        return None
    for prefix in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        marker = os.path.join(prefix, ".catkin")
        if not prefix or not os.path.isfile(marker):
            continue
        try:
            with open(marker) as f:
                sources = [s for s in f.read().split(";") if s.strip()]
        except (OSError, UnicodeDecodeError):
            continue
        if any(_under(folder, (os.path.realpath(s.strip()),)) for s in sources + [prefix]):
            return prefix
    return None


def _built_python(pkg: str) -> List[str]:
    """The Python folders of `pkg` in the space that built it (see built_space)."""
    space = built_space(pkg)
    if space is None:
        return []
    return sorted(glob.glob(os.path.join(space, "lib", "python3*", "*-packages", pkg)))


def definition_path(pkg: str, base: str, kind: str = "msg") -> Optional[str]:
    """The `.msg`/`.srv` file of `pkg/base` as rosmsg finds it: in the package's folder, else in
    the share folder of the space that built the package (where add_action_files puts the action's
    messages); None when there is none (or the names are not a package's and a type's)."""
    if not (_NAME.match(pkg) and _NAME.match(base)) or kind not in ("msg", "srv"):
        return None
    folders = []
    try:
        folders.append(_rospack().get_path(pkg))
    except rospkg.ResourceNotFound:
        pass
    space = built_space(pkg)
    if space is not None:
        folders.append(os.path.join(space, "share", pkg))
    for folder in folders:
        path = os.path.join(folder, kind, "%s.%s" % (base, kind))
        if os.path.isfile(path):
            return path
    return None


def read_definition(path: str, kind: str = "msg") -> str:
    """A definition file's text, read as data: a regular file (not a link, a fifo or a device)
    named like a definition, at most MAX_DEFINITION_BYTES of UTF-8. Raises InterfaceError."""
    name = os.path.basename(path)
    real = os.path.realpath(path)
    if os.path.basename(real) != name or os.path.basename(os.path.dirname(real)) != kind:
        raise InterfaceError("%s is a link to another file: a definition must be a file of its own" % path)
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError as err:
        raise InterfaceError("cannot read %s: %s" % (path, err.strerror)) from None
    with os.fdopen(fd, "rb") as f:
        if not stat.S_ISREG(os.fstat(f.fileno()).st_mode):
            raise InterfaceError("%s is not a regular file" % path)
        data = f.read(MAX_DEFINITION_BYTES + 1)
    if len(data) > MAX_DEFINITION_BYTES:
        raise InterfaceError("%s is longer than %d bytes" % (path, MAX_DEFINITION_BYTES))
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as err:
        raise InterfaceError("%s is not UTF-8 text (byte %d)" % (path, err.start)) from None


def definition_text(msg_type: str) -> Optional[str]:
    """The text of message type `pkg/Type`'s .msg file, or None when there is none (raises
    InterfaceError when it cannot be read): how dependencies are found."""
    pkg, base = _split(msg_type, "msg")
    path = definition_path(pkg, base, "msg")
    return None if path is None else read_definition(path, "msg")


def generated_module_exists(pkg: str, base: str, kind: str = "msg") -> bool:
    """Whether the space that built `pkg` (built_space) has its generated `<kind>/_<base>.py`,
    found by path, without importing anything."""
    return any(os.path.isfile(os.path.join(p, kind, "_%s.py" % base)) for p in _built_python(pkg))


def _from_files(kind: str, pkg: str, base: str) -> type:
    type_name = "%s/%s" % (pkg, base)
    if built_space(pkg) is None:
        raise NotBuilt("%s/%s is not built: no workspace on the path built package %s" % (pkg, base, pkg))
    if not generated_module_exists(pkg, base, kind):
        raise NotBuilt("%s/%s is not built (no generated Python module %s/%s/_%s.py in %s)"
                       % (pkg, base, pkg, kind, base, built_space(pkg)))
    path = definition_path(pkg, base, kind)
    if path is None:
        raise NotBuilt("%s/%s has no definition (no %s/%s/%s.%s in package %s)" % (pkg, base, pkg, kind, base, kind,
                                                                                 pkg))
    text = read_definition(path, kind)
    if kind == "msg":
        return message_class_from_text(type_name, text, definition_text)
    return service_class_from_text(type_name, text, definition_text)


# -- from definition text to class ---------------------------------------------------------------

def message_class_from_text(msg_type: str, text: str, find: FindDefinition = lambda _: None) -> type:
    """The genpy class of message `msg_type` defined by `text`; `find(type)` gives the text of each
    message type it uses (None: unknown). Raises InterfaceError for anything genpy could not make
    into a working class."""
    pkg, base = _split(msg_type, "msg")
    context = genmsg.MsgContext.create_default()
    spec = _parse(lambda: genmsg.msg_loader.load_msg_from_string(context, text, msg_type), msg_type, text)
    specs = _with_dependencies(context, [spec], find)
    return _generate(context, spec, specs)


def service_class_from_text(srv_type: str, text: str, find: FindDefinition = lambda _: None) -> type:
    """The class of service `srv_type` defined by `text`, built like a generated one: `_type`,
    `_md5sum` (genmsg's, over request and response) and dynamic `_request_class`/`_response_class`."""
    pkg, base = _split(srv_type, "srv")
    context = genmsg.MsgContext.create_default()
    spec = _parse(lambda: genmsg.msg_loader.load_srv_from_string(context, text, srv_type), srv_type, text)
    specs = _with_dependencies(context, [spec.request, spec.response], find)
    request = _generate(context, spec.request, specs)
    response = _generate(context, spec.response, specs)
    md5 = _genmsg(lambda: genmsg.compute_md5(context, spec), srv_type)
    return type(base, (object,), {
        "__doc__": "Service %s, built from its definition by course_milestones.messages." % srv_type,
        "_type": srv_type, "_md5sum": md5, "_request_class": request, "_response_class": response})


def _parse(load: Callable[[], object], type_name: str, text: str):
    if not isinstance(text, str):
        raise InterfaceError("the definition of %s is not text" % type_name)
    if len(text.encode("utf-8", errors="replace")) > MAX_DEFINITION_BYTES:
        raise InterfaceError("the definition of %s is longer than %d bytes" % (type_name, MAX_DEFINITION_BYTES))
    return _genmsg(load, type_name)


def _genmsg(call: Callable[[], object], type_name: str):
    """genmsg's answer, or its complaint as an InterfaceError (genmsg evaluates nothing: any error
    it raises is about the definition)."""
    try:
        return call()
    except RecursionError:
        raise InterfaceError("the definition of %s nests too deeply" % type_name) from None
    except Exception as err:  # noqa: BLE001 - genmsg raises InvalidMsgSpec, ValueError, KeyError, ...
        reason = str(err).strip() or type(err).__name__
        raise InterfaceError("the definition of %s is invalid: %s" % (type_name, _short(reason))) from None


def _short(text: str, limit: int = 300) -> str:
    text = " ".join(text.split())
    return text if len(text) <= limit else text[:limit] + "..."


def _with_dependencies(context, roots: List, find: FindDefinition) -> Dict[str, object]:
    """Every message spec the roots use, loaded through `find`, checked, in an order where each
    comes after those it uses; registers their dependencies in `context` for genmsg."""
    specs: Dict[str, object] = {}
    uses: Dict[str, List[str]] = {}
    pending = list(roots)
    while pending:
        spec = pending.pop()
        if spec.full_name in specs:
            continue
        _check(spec)
        specs[spec.full_name] = spec
        uses[spec.full_name] = []
        for field_type in spec.types:
            dep = genmsg.msgs.bare_msg_type(field_type)
            if genmsg.msgs.is_builtin(dep):
                continue
            uses[spec.full_name].append(dep)
            if dep in specs or any(p.full_name == dep for p in pending):
                continue
            if len(specs) + len(pending) >= MAX_TYPES:
                raise InterfaceError("%s uses more than %d message types" % (roots[0].full_name, MAX_TYPES))
            _split(dep, "msg")
            text = find(dep)
            if text is None:
                raise InterfaceError("%s uses %s, whose definition is not found (no %s/msg/%s.msg)"
                                     % (spec.full_name, dep, *dep.split("/")))
            pending.append(_parse(lambda t=text, d=dep: genmsg.msg_loader.load_msg_from_string(context, t, d),
                                  dep, text))
    order = _ordered(uses)
    _check_sizes(specs, order)
    for name in order:
        _genmsg(lambda n=name: genmsg.msg_loader.load_msg_depends(context, specs[n], {}), name)
    return {name: specs[name] for name in order}


def _ordered(uses: Dict[str, List[str]]) -> List[str]:
    """The types, each after those it uses (depth first, without recursion); a type that contains
    itself is an InterfaceError."""
    order: List[str] = []
    state: Dict[str, str] = {}
    for start in uses:
        if start in state:
            continue
        state[start] = "open"
        stack = [(start, iter(uses[start]))]
        while stack:
            name, deps = stack[-1]
            dep = next(deps, None)
            if dep is None:
                stack.pop()
                state[name] = "done"
                order.append(name)
            elif state.get(dep) == "open":
                path = [n for n, _ in stack]
                cycle = path[path.index(dep):] + [dep]
                raise InterfaceError("%s contains itself (%s): a message cannot" % (dep, " -> ".join(cycle)))
            elif dep not in state:
                state[dep] = "open"
                stack.append((dep, iter(uses[dep])))
    return order


def _check(spec) -> None:
    """What genmsg accepts but genpy cannot turn into safe, working Python: names that are not
    plain identifiers, types other than `[pkg/]Type[N]`, constant values genpy would not write
    back as the same literal, and fields clashing with constants or the class's methods."""
    where = spec.full_name
    names: Set[str] = set()
    for field_type, name in zip(spec.types, spec.names):
        if not _NAME.match(name):
            raise InterfaceError("%s: %r is not a valid field name (a letter, then letters, digits or _)"
                                 % (where, name))
        if not _FIELD_TYPE.match(field_type):
            raise InterfaceError("%s: %r is not a valid field type (Type, pkg/Type, Type[] or Type[N])"
                                 % (where, field_type))
        if _python_name(name) in _CLASS_BODY_NAMES:
            raise InterfaceError("%s: a field cannot be named %s (genpy's classes have a method of that name)"
                                 % (where, name))
        names.add(_python_name(name))
    for constant in spec.constants:
        if not _NAME.match(constant.name):
            raise InterfaceError("%s: %r is not a valid constant name (a letter, then letters, digits or _)"
                                 % (where, constant.name))
        if _python_name(constant.name) in names:
            raise InterfaceError("%s: %s is both a field and a constant" % (where, constant.name))
        names.add(_python_name(constant.name))
        _check_constant(where, constant)


def _python_name(name: str) -> str:
    """The name genpy gives a field or constant in Python (keywords and `self` get a `_`)."""
    import keyword
    return name + "_" if name in keyword.kwlist or name == "self" else name


def _check_constant(where: str, constant) -> None:
    kind, text, value = constant.type, constant.val_text, constant.val
    if kind == "string":
        if "\\" in text or _CONTROL.search(text):
            raise InterfaceError("%s: the string constant %s holds a backslash or a control character, which "
                                 "the checks do not support" % (where, constant.name))
        return
    pattern = _FLOAT if kind in ("float32", "float64") else _BOOL if kind == "bool" else _INT
    if not pattern.match(text) or (isinstance(value, float) and not math.isfinite(value)):
        raise InterfaceError("%s: the constant %s = %r is not a plain %s literal" % (where, constant.name, text, kind))


def _check_sizes(specs: Dict[str, object], order: List[str]) -> None:
    """A default message allocates its fixed-size arrays: keep that small (order: used types first)."""
    size: Dict[str, int] = {}
    for name in order:
        total = 1
        for field_type in specs[name].types:
            base, is_array, length = genmsg.msgs.parse_type(field_type)
            one = size.get(base, 1)
            total += (length * one) if is_array and length is not None else 1 if is_array else one
            if total > MAX_DEFAULT_ELEMENTS:
                raise InterfaceError("%s holds more than %d values once its fixed-size arrays are filled"
                                     % (name, MAX_DEFAULT_ELEMENTS))
        size[name] = total


def _canonical(spec) -> str:
    """The definition rebuilt from its checked parts: the md5 text's lines (constants, then fields,
    with resolved types), which parse back to the same spec and md5 and hold nothing else."""
    lines = ["%s %s=%s" % (c.type, c.name, c.val_text) for c in spec.constants]
    lines += ["%s %s" % (t, n) for t, n in zip(spec.types, spec.names)]
    return "\n".join(lines)


def _generate(context, root, specs: Dict[str, object]) -> type:
    """genpy's dynamic class of `root`, generated from canonical texts, then given the original
    full text (data) and checked to carry genmsg's md5 of the original."""
    used = [name for name in specs if name != root.full_name and name in _closure(root.full_name, specs)]
    separator = "\n" + "=" * 80 + "\n"
    text = separator.join([_canonical(root)] + ["MSG: %s\n%s" % (name, _canonical(specs[name])) for name in used])
    md5 = _genmsg(lambda: genmsg.compute_md5(context, root), root.full_name)
    full_text = _genmsg(lambda: genmsg.compute_full_text(context, root), root.full_name)
    saved_path, saved_modules = list(sys.path), set(sys.modules)
    try:
        classes = genpy.dynamic.generate_dynamic(root.full_name, text)
    except Exception as err:  # noqa: BLE001 - _check lets through only what genpy handles; say so if not
        raise InterfaceError("genpy could not generate a class for %s: %s" % (root.full_name, _short(str(err)))) \
            from None
    finally:  # generate_dynamic leaves its temporary folder on sys.path and its module imported
        sys.path[:] = saved_path
        for name in set(sys.modules) - saved_modules:
            if name.startswith("tmp"):
                sys.modules.pop(name, None)
    cls = classes.get(root.full_name)
    if cls is None or cls._md5sum != md5:
        raise InterfaceError("genpy's class for %s does not match its definition (md5 %s, expected %s)"
                             % (root.full_name, getattr(cls, "_md5sum", None), md5))
    cls._full_text = full_text
    return cls


def _closure(name: str, specs: Dict[str, object]) -> Set[str]:
    """`name` and every message type it uses, directly or not."""
    seen: Set[str] = set()
    pending = [name]
    while pending:
        current = pending.pop()
        if current in seen or current not in specs:
            continue
        seen.add(current)
        pending += [genmsg.msgs.bare_msg_type(t) for t in specs[current].types]
    return seen


__all__ = ["InterfaceError", "NotBuilt", "NoService", "message_class", "service_class", "service_class_by_name",
           "message_class_from_text", "service_class_from_text", "imports_safely", "definition_path",
           "read_definition", "definition_text", "generated_module_exists", "built_space", "trusted_path", "forget", "genpy"]
