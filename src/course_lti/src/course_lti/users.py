"""Who each student is in the LMS: the user id (LTI `sub`) a score is posted for.

Two sources, one per way of grading:

- the hub's `<data>/lti-users.json`, written by the hub's LTI login when a student opens the
  course from the LMS: hub user name -> {"iss": ..., "sub": ..., "deployment_id": ...,
  "lineitems_url": ...} (lineitems_url, the launch's AGS endpoint claim, optional);
- for a class graded elsewhere (`grade --lti`), a CSV with a header: `student,user_id`, one row
  per student (the student's folder or archive name as the gradebook shows it, and their LMS
  user id), optional columns `iss` and `lineitems_url`.

A student missing from the file has no LMS identity yet: their scores stay pending.
"""
from __future__ import annotations

import csv
import json
from typing import Dict, NamedTuple

from course_lti.config import ConfigError


class LmsUser(NamedTuple):
    """One student's identity in the LMS."""

    sub: str  # the LTI user id, `userId` of a score
    iss: str = ""  # the platform that said so ("": not recorded)
    deployment_id: str = ""
    lineitems_url: str = ""  # the course context's line items, as the student's launch gave it


def _from_json(path: str, data: object) -> Dict[str, LmsUser]:
    if not isinstance(data, dict):
        raise ConfigError(["%s: (the file): must map each hub user name to {iss, sub, ...}" % path])
    users: Dict[str, LmsUser] = {}
    problems = []
    for name, entry in data.items():
        if not isinstance(entry, dict) or not isinstance(entry.get("sub"), str) or not entry["sub"]:
            problems.append("%s: %s: must be an object with a non-empty string sub" % (path, name))
            continue
        users[str(name)] = LmsUser(entry["sub"], str(entry.get("iss") or ""), str(entry.get("deployment_id") or ""),
                                   str(entry.get("lineitems_url") or ""))
    if problems:
        raise ConfigError(problems)
    return users


def _from_csv(path: str, text: str) -> Dict[str, LmsUser]:
    rows = list(csv.DictReader(text.splitlines()))
    if not rows and "student" not in text:
        return {}
    fields = set(rows[0]) if rows else set()
    if not {"student", "user_id"} <= fields:
        raise ConfigError(["%s: (the header): needs the columns student,user_id (found: %s)"
                           % (path, ",".join(sorted(f for f in fields if f)))])
    users: Dict[str, LmsUser] = {}
    problems = []
    for number, row in enumerate(rows, 2):
        student, sub = (row.get("student") or "").strip(), (row.get("user_id") or "").strip()
        if not student or not sub:
            problems.append("%s: line %d: needs a student and a user_id" % (path, number))
            continue
        users[student] = LmsUser(sub, (row.get("iss") or "").strip(), "", (row.get("lineitems_url") or "").strip())
    if problems:
        raise ConfigError(problems)
    return users


def load(path: str, missing_ok: bool = False) -> Dict[str, LmsUser]:
    """Student -> LMS identity from `path` (.json: the hub's file; else CSV). ConfigError when the
    file is malformed, or missing unless `missing_ok` (the hub's, before any student opened the
    course from the LMS: then nobody is known and every score stays pending); the message says
    which file and what it should hold."""
    try:
        with open(path) as stream:
            text = stream.read()
    except FileNotFoundError as err:
        if missing_ok:
            return {}
        raise ConfigError(["%s: (the file): missing: it maps each student to their LMS user id (the hub's LTI "
                           "login writes it as students open the course from the LMS; for grade --lti, a CSV "
                           "student,user_id)" % path]) from err
    except OSError as err:
        raise ConfigError(["%s: (the file): cannot read it: %s" % (path, err.strerror or err)]) from err
    if path.endswith(".json"):
        try:
            data = json.loads(text or "{}")
        except ValueError as err:
            raise ConfigError(["%s: (the file): not JSON: %s" % (path, err)]) from err
        return _from_json(path, data)
    return _from_csv(path, text)
