"""What a grading folder keeps of its postings, beside its gradebook:

- `lti-posted.json`: every score the LMS took (per line item container, line item and LMS user:
  the digest of what was sent, so a second run sends only what is missing or changed) and the
  line items found or created (their URLs, so a second run need not look them up);
- `lti-pending.json`: every score that could not be posted (the LMS down or refusing, a student
  it does not know yet), with the score itself and why. Written anew by each run (removed when
  nothing is pending): the next run of the same command posts them, nothing is lost.

Both are written whole to a temporary file, then renamed: a killed run leaves the old or the new.
"""
from __future__ import annotations

import hashlib
import json
import os
from typing import Dict, List, NamedTuple, Optional

POSTED = "lti-posted.json"
PENDING = "lti-pending.json"
FORMAT = 1


def key(*parts: str) -> str:
    """One unambiguous key of several strings (URLs may hold any separator)."""
    return json.dumps(list(parts))


def digest(payload: Dict[str, object]) -> str:
    """What identifies a score as sent: its JSON, keys sorted."""
    return hashlib.sha256(json.dumps(payload, sort_keys=True).encode("utf-8")).hexdigest()


def write_json(path: str, data: object) -> None:
    """`data` into `path`, whole or not at all."""
    partial = path + ".partial"
    with open(partial, "w") as stream:
        json.dump(data, stream, indent=2, sort_keys=True)
        stream.write("\n")
    os.replace(partial, path)


def read_json(path: str) -> Optional[dict]:
    """The JSON object in `path`, None when there is none (a damaged file is set aside, not trusted)."""
    try:
        with open(path) as stream:
            data = json.load(stream)
    except FileNotFoundError:
        return None
    except (OSError, ValueError):
        os.replace(path, path + ".damaged")
        return None
    return data if isinstance(data, dict) and data.get("format") == FORMAT else None


class Posted:
    """The record of one grading folder's postings (POSTED)."""

    def __init__(self, out: str) -> None:
        self.path = os.path.join(out, POSTED)
        data = read_json(self.path) or {}
        self.lineitems: Dict[str, str] = dict(data.get("lineitems") or {})
        self.scores: Dict[str, Dict[str, str]] = dict(data.get("scores") or {})

    def lineitem(self, container: str, resource_id: str, tag: str) -> Optional[str]:
        return self.lineitems.get(key(container, resource_id, tag))

    def remember_lineitem(self, container: str, resource_id: str, tag: str, url: str) -> None:
        self.lineitems[key(container, resource_id, tag)] = url

    def forget_lineitem(self, container: str, resource_id: str, tag: str) -> None:
        self.lineitems.pop(key(container, resource_id, tag), None)

    def already(self, container: str, resource_id: str, user_id: str, payload: Dict[str, object]) -> bool:
        """Whether exactly this score was posted before."""
        done = self.scores.get(key(container, resource_id, user_id))
        return done is not None and done.get("digest") == digest(payload)

    def remember(self, container: str, resource_id: str, user_id: str, student: str,
                 payload: Dict[str, object], when: str) -> None:
        self.scores[key(container, resource_id, user_id)] = {
            "student": student, "digest": digest(payload), "scoreGiven": str(payload.get("scoreGiven")),
            "timestamp": str(payload.get("timestamp")), "posted": when}

    def save(self) -> None:
        write_json(self.path, {"format": FORMAT, "lineitems": self.lineitems, "scores": self.scores})


class Pending(NamedTuple):
    """A score not posted, and why."""

    student: str
    user_id: str  # "" when the LMS does not know the student yet
    container: str
    lineitem: Dict[str, object]  # the line item's payload
    score: Dict[str, object]  # the score's payload
    why: str


def save_pending(out: str, pending: List[Pending], when: str) -> str:
    """The pending file for `pending` (removed when there is none); its path."""
    path = os.path.join(out, PENDING)
    if not pending:
        if os.path.exists(path):
            os.remove(path)
        return path
    write_json(path, {"format": FORMAT, "written": when, "pending": [p._asdict() for p in pending]})
    return path


def load_pending(out: str) -> List[Pending]:
    """The scores a grading folder lists as pending."""
    data = read_json(os.path.join(out, PENDING)) or {}
    found = []
    for entry in data.get("pending") or []:
        try:
            found.append(Pending(**entry))
        except TypeError:
            continue
    return found
