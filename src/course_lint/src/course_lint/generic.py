"""Generic Python mutants from mutmut (PyPI), for `course-lint --mutmut`: a number, operator,
string, keyword or assignment changed anywhere in a node, beside the ROS-specific operators.

Optional: mutmut is not a dependency of course_lint (the grading never needs it), so it is loaded
when asked for. Its per-mutant interface (`list_mutations`, `mutate`) is mutmut 2's
(`pip install "mutmut<3"`); mutmut 3 mutates a whole project for its own test runner only.
"""
from __future__ import annotations

import importlib
from typing import List

from course_lint.mutants import PYTHON, Operator

INSTALL = 'pip install "mutmut<3"'


class Unavailable(RuntimeError):
    """mutmut is missing, or has no per-mutant interface."""


def load_mutmut():
    try:
        mutmut = importlib.import_module("mutmut")  # optional: see the module's docstring
    except ImportError:
        raise Unavailable("--mutmut needs mutmut 2: %s" % INSTALL) from None
    if not all(hasattr(mutmut, name) for name in ("Context", "list_mutations", "mutate")):
        raise Unavailable("--mutmut needs mutmut 2's per-mutant interface (%s); this is mutmut %s"
                          % (INSTALL, getattr(mutmut, "__version__", "3 or later")))
    return mutmut


def operator() -> Operator:
    """The `mutmut` operator: every mutation mutmut finds in a Python file. Unavailable without it."""
    mutmut = load_mutmut()

    def sites(text: str) -> List[str]:
        try:
            found = mutmut.list_mutations(mutmut.Context(source=text, filename="node.py"))
            return [mutmut.mutate(mutmut.Context(source=text, filename="node.py", mutation_id=m))[0] for m in found]
        except Exception:  # mutmut's parser (parso) on a file it cannot mutate: no sites
            return []
    return Operator("mutmut", "a generic mutation from mutmut: a number, operator, string or keyword changed",
                    {PYTHON: sites})
