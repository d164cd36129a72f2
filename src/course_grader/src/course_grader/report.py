"""report.html for the class: a table of verdicts, then each student's reasons, log tails and
the canvas snapshots of their turtlesim runs (linked relative to the report)."""
from __future__ import annotations

import html
import os
from typing import Dict, List, Sequence

from course_milestones.milestone import Milestone

from course_grader.gradebook import columns
from course_grader.verdict import Verdict

STYLE = """body{font-family:sans-serif;margin:1em}table{border-collapse:collapse}
td,th{border:1px solid #ccc;padding:3px 6px;text-align:center}.pass{background:#cfc}.fail{background:#fcc}
pre{background:#f6f6f6;padding:6px;white-space:pre-wrap;max-height:25em;overflow:auto}
img{width:200px;border:1px solid #999;margin:2px}"""


def _cell(v: Verdict, anchor: str) -> str:
    css, word = ("pass", "%g" % v.points) if v.passed else ("fail", "0")
    return '<td class="%s" title="%s"><a href="#%s">%s</a></td>' % (
        css, html.escape(v.reason.splitlines()[0] if v.reason else "passed"), anchor, word)


def render(verdicts: Sequence[Verdict], order: Sequence[Milestone], report_dir: str, isolation: str = "") -> str:
    milestones = columns(verdicts, order)
    by_student: Dict[str, List[Verdict]] = {}
    for v in verdicts:
        by_student.setdefault(v.student, []).append(v)
    out = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>Class report</title>",
           "<style>%s</style></head><body><h1>Class report</h1>" % STYLE,
           "<p>Isolation of student code: %s</p>" % html.escape(isolation or "not recorded"),
           "<table><tr><th>student</th>%s<th>total</th></tr>"
           % "".join("<th>%s</th>" % html.escape(m.name) for m in milestones)]
    for student, graded in by_student.items():
        named = {v.milestone.name: v for v in graded}
        cells = "".join(_cell(named[m.name], "%s-%s" % (student, m.name)) if m.name in named else "<td></td>"
                        for m in milestones)
        total = sum(v.points for v in graded)
        out.append('<tr><th><a href="#%s">%s</a></th>%s<td>%g / %g</td></tr>' % (
            html.escape(student), html.escape(student), cells, total, sum(v.milestone.points for v in graded)))
    out.append("</table>")
    for student, graded in by_student.items():
        out.append('<h2 id="%s">%s</h2>' % (html.escape(student), html.escape(student)))
        for v in graded:
            out.append('<h3 id="%s-%s" class="%s">%s: %s (%s) &mdash; %s, %.1f s</h3>' % (
                html.escape(student), html.escape(v.milestone.name), "pass" if v.passed else "fail",
                html.escape(v.milestone.name), html.escape(v.milestone.title), html.escape(v.milestone.text),
                "passed" if v.passed else "failed", v.elapsed))
            if not v.passed or v.logs or v.notes:
                out.append("<pre>%s</pre>" % html.escape(v.output()))
            for png in v.canvases():
                rel = os.path.relpath(png, report_dir)
                out.append('<a href="%s"><img src="%s" alt="%s"></a>' % (html.escape(rel), html.escape(rel),
                                                                          html.escape(os.path.basename(png))))
    out.append("</body></html>")
    return "\n".join(out)


def write(path: str, verdicts: Sequence[Verdict], order: Sequence[Milestone], isolation: str = "") -> None:
    with open(path, "w") as f:
        f.write(render(verdicts, order, os.path.dirname(os.path.abspath(path)), isolation))
