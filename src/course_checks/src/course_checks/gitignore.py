"""A tree's files as git would list them where there is no git: every file the .gitignore at its
root does not ignore. The course image copies the checkout without .git: the autograder zip
(course_grader.autograder) and the check that a grading leaves the checkout as it was
(course_testkit.sample_grading) then read the tree itself."""
from __future__ import annotations

import fnmatch
import os
from typing import Iterable, List


def not_ignored_files(repo: str) -> List[str]:
    """Every file under `repo` that the .gitignore at its root does not ignore (its patterns:
    `/anchored`, `folder/`, `*.glob`, `name`), .git itself left out."""
    patterns: List[str] = []
    ignore_file = os.path.join(repo, ".gitignore")
    if os.path.exists(ignore_file):
        with open(ignore_file) as f:
            patterns = [line.strip() for line in f if line.strip() and not line.startswith("#")]
    found = []
    for folder, dirs, files in os.walk(repo):
        rel_folder = os.path.relpath(folder, repo)
        rel_folder = "" if rel_folder == "." else rel_folder + "/"
        dirs[:] = [d for d in dirs if d != ".git" and not ignored(rel_folder + d + "/", patterns)]
        found += [rel_folder + name for name in files if not ignored(rel_folder + name, patterns)]
    return found


def ignored(rel: str, patterns: Iterable[str]) -> bool:
    """Whether .gitignore `patterns` ignore the path `rel` (a folder's ends with '/')."""
    name = rel.rstrip("/").rsplit("/", 1)[-1]
    for pattern in patterns:
        folder_only = pattern.endswith("/")
        body = pattern.strip("/")
        if folder_only and not rel.endswith("/"):
            continue
        if pattern.startswith("/") or "/" in body:
            if fnmatch.fnmatch(rel.rstrip("/"), body):
                return True
        elif fnmatch.fnmatch(name, body):
            return True
    return False
