"""A course's sample submissions (courses/<course>/samples/) as a student hands them in.

A sample with a `derive.json` is a variant of another folder of its course (its reference
solution, another sample), so that neither code nor answers are written twice: it is made in a
temporary folder before grading, from {"copy": [[source, target], ...]} (folders of the course,
relative to the course folder: `solution/chatter`, `samples/other`; copied into the sample, one
over another), then the sample's own files over them, then
{"remove": [path, ...]} and {"replace": [[path, old, new], ...]} (each `old` must be there).
"""
from __future__ import annotations

import json
import shutil
from pathlib import Path

CHECKOUT = Path(__file__).resolve().parents[4]
SAMPLES_DIR = CHECKOUT / "courses" / "robotics_labs" / "samples"  # the built-in course's


def materialise(sample: Path, dest: Path) -> Path:
    """The sample as handed in: itself, or for a derived sample (derive.json) the folder it
    describes, made under `dest`."""
    recipe_path = sample / "derive.json"
    if not recipe_path.is_file():
        return sample
    recipe = json.loads(recipe_path.read_text())
    made = dest / sample.name
    shutil.rmtree(made, ignore_errors=True)
    for source, target in recipe.get("copy", []):
        shutil.copytree(sample.parent.parent / source, made / target, dirs_exist_ok=True,
                        ignore=shutil.ignore_patterns("__pycache__", "*.pyc"))
    shutil.copytree(sample, made, dirs_exist_ok=True, ignore=shutil.ignore_patterns("derive.json"))
    for rel in recipe.get("remove", []):
        path = made / rel
        shutil.rmtree(path) if path.is_dir() else path.unlink()
    for rel, old, new in recipe.get("replace", []):
        text = (made / rel).read_text()
        assert old in text, "%s: derive.json replaces %r, which %s does not hold" % (sample.name, old, rel)
        (made / rel).write_text(text.replace(old, new))
    return made
