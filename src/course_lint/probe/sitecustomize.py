"""course-lint's probe, loaded by Python at start-up in each process of the reference's lint run:
this folder is first on their PYTHONPATH (the environment hook of the package course_lint_probe,
which course-lint adds to the reference it grades; course_lint.probe says what it records). Then
the sitecustomize this one hides, if the system has one, runs as it would have."""
import importlib.machinery
import importlib.util
import os
import sys


def _system_sitecustomize() -> None:
    here = os.path.dirname(os.path.abspath(__file__))
    others = [p for p in sys.path if os.path.abspath(p or os.curdir) != here]
    spec = importlib.machinery.PathFinder.find_spec("sitecustomize", others)
    if spec is not None and spec.loader is not None:
        spec.loader.exec_module(importlib.util.module_from_spec(spec))


try:
    from course_lint import probe
    probe.start()
except Exception:  # noqa: BLE001 - a process of the run must start whatever the probe does
    pass
_system_sitecustomize()
