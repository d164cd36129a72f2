"""genpy's check_type() verdicts, one JSON line in, one out: the oracle processes of
test_numpy_deferral's property test, which runs one per way of loading genpy and compares them.

    python3 check_type_oracle.py numpy-first|numpy-later|no-numpy

numpy-first: numpy imported before genpy (upstream's list, or the hook doing nothing);
numpy-later: genpy.message first, then numpy; no-numpy: numpy never imported.
First line out: {"numpy_before_genpy": ..., "float_types": type name of _valid_float_types}.
Each line in: [field_type, value], a value being ["float", x], ["int", n], ["bool", b], ["str", s],
["none"], ["float_subclass", x], ["np", numpy type name, n], or ["list" | "tuple", [values]].
Each line out: "ok" or "<exception type>: <message>".
"""
from __future__ import annotations

import json
import sys


class FloatSubclass(float):
    """A float that is not `float`: check_type looks at the exact type."""


def build(spec: list) -> object:
    kind = spec[0]
    if kind == "np":
        import numpy
        return getattr(numpy, spec[1])(spec[2])
    if kind in ("list", "tuple"):
        items = [build(item) for item in spec[1]]
        return items if kind == "list" else tuple(items)
    if kind == "float_subclass":
        return FloatSubclass(spec[1])
    if kind == "none":
        return None
    return {"float": float, "int": int, "bool": bool, "str": str}[kind](spec[1])


def verdict(check_type, field_type: str, value: object) -> str:
    try:
        check_type("field", field_type, value)
    except Exception as error:  # the verdict is the exception, whichever it is
        return "%s: %s" % (type(error).__name__, error)
    return "ok"


def main(mode: str) -> None:
    if mode == "numpy-first":
        import numpy  # noqa: F401
    import genpy.message
    before = "numpy" in sys.modules
    if mode == "numpy-later":
        import numpy  # noqa: F401,F811
    print(json.dumps({"numpy_before_genpy": before,
                      "float_types": type(genpy.message._valid_float_types).__name__}), flush=True)
    for line in sys.stdin:
        field_type, spec = json.loads(line)
        print(json.dumps(verdict(genpy.message.check_type, field_type, build(spec))), flush=True)
    if mode == "no-numpy" and "numpy" in sys.modules:
        print(json.dumps("numpy was imported"), flush=True)


if __name__ == "__main__":
    main(sys.argv[1])
