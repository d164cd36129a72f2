"""report.html for the class: first the class at a glance (class_view: per milestone pass rate and
median run time, the scores' histogram, the failures grouped by cause), the submissions too alike
(similarity, never part of a verdict), then a table of verdicts, then each student's reasons, log
tails and the canvas snapshots of their turtlesim runs (linked relative to the report). The
tables are plain HTML; a little JavaScript sorts them (click a heading) and filters the verdicts
(by student, milestone or failure group), with no server."""
from __future__ import annotations

import html
import os
from typing import Dict, List, Sequence

from course_format.milestone import Milestone

from course_grader import class_view, similarity
from course_grader.gradebook import columns
from course_grader.verdict import Verdict

STYLE = """body{font-family:sans-serif;margin:1em}table{border-collapse:collapse}
td,th{border:1px solid #ccc;padding:3px 6px;text-align:center}.pass{background:#cfc}.fail{background:#fcc}
pre{background:#f6f6f6;padding:6px;white-space:pre-wrap;max-height:25em;overflow:auto}
img{width:200px;border:1px solid #999;margin:2px}img.figure{width:auto;border:0}
th.sort{cursor:pointer}td.left,th.left{text-align:left}.side{display:flex;gap:6px}.side pre{flex:1}"""
# Sort a table by the clicked heading (numbers as numbers), and show only the verdict rows whose
# text or failure groups hold the filter's words. Without JavaScript the tables read as they are.
SCRIPT = """<script>
function sortBy(th){var t=th.closest('table'),i=th.cellIndex,rows=[].slice.call(t.rows,1),
 up=th.dataset.up!=='1';th.dataset.up=up?'1':'0';
 function key(r){var c=r.cells[i],x=c?c.textContent.trim():'',n=parseFloat(x);return isNaN(n)?x.toLowerCase():n;}
 rows.sort(function(a,b){var x=key(a),y=key(b);return (x<y?-1:x>y?1:0)*(up?1:-1);});
 rows.forEach(function(r){r.parentNode.appendChild(r);});}
function filterRows(words){document.getElementById('filter').value=words;
 var w=words.toLowerCase().split(/\\s+/).filter(Boolean);
 [].forEach.call(document.querySelectorAll('#verdicts tr[data-groups]'),function(r){
  var text=(r.textContent+' '+r.dataset.groups).toLowerCase();
  r.style.display=w.every(function(x){return text.indexOf(x)>=0;})?'':'none';});}
document.querySelectorAll('th.sort').forEach(function(th){th.onclick=function(){sortBy(th);};});
document.getElementById('filter').hidden=false;
</script>"""



def _cell(v: Verdict, anchor: str) -> str:
    css, word = ("pass", "%g" % v.points) if v.passed else ("fail", "0")
    return '<td class="%s" title="%s"><a href="#%s">%s</a></td>' % (
        css, html.escape(v.reason.splitlines()[0] if v.reason else "passed"), anchor, word)


def _glance(verdicts: Sequence[Verdict], order: Sequence[Milestone], report_dir: str) -> List[str]:
    """The class at a glance: per milestone, the histogram, the failure groups."""
    out = ["<h2 id='glance'>The class at a glance</h2>",
           "<table><tr><th class='sort left'>milestone</th><th class='sort'>graded</th><th class='sort'>passed</th>"
           "<th class='sort'>pass rate</th><th class='sort'>median run, s</th></tr>"]
    for st in class_view.milestone_stats(verdicts, order):
        out.append("<tr><td class='left'>%s</td><td>%d</td><td>%d</td><td>%.0f%%</td><td>%.1f</td></tr>" % (
            html.escape(st.milestone.name), st.graded, st.passed, 100 * st.rate, st.median_s))
    out.append("</table>")
    png = class_view.histogram(os.path.join(report_dir, class_view.HISTOGRAM_PNG), verdicts)
    if png:
        out.append("<p><img class='figure' src='%s' alt='histogram of the students&#39; scores'></p>"
                   % html.escape(os.path.relpath(png, report_dir)))
    groups = class_view.failure_groups(verdicts)
    out.append("<h3>Failures by cause</h3>")
    if not groups:
        out.append("<p>No failure.</p>")
        return out
    out.append("<table><tr><th class='sort'>count</th><th class='sort left'>milestone</th>"
               "<th class='sort left'>cause</th><th class='left'>students</th></tr>")
    for g in groups:
        key = "%s:%s" % (g.milestone, g.cause)
        students = ", ".join('<a href="#%s-%s">%s</a>' % (html.escape(s), html.escape(g.milestone), html.escape(s))
                             for s in g.students)
        out.append("<tr><td>%d</td><td class='left'>%s</td><td class='left'><a href='#verdicts' "
                   "onclick=\"filterRows('%s')\">%s</a> <small>(%s)</small></td><td class='left'>%s</td></tr>"
                   % (len(g.students), html.escape(g.milestone), html.escape(key), html.escape(g.label),
                      html.escape(g.cause), students))
    out.append("</table>")
    return out


def render(verdicts: Sequence[Verdict], order: Sequence[Milestone], report_dir: str, isolation: str = "",
           similar: Sequence[similarity.Pair] = ()) -> str:
    milestones = columns(verdicts, order)
    by_student: Dict[str, List[Verdict]] = {}
    for v in verdicts:
        by_student.setdefault(v.student, []).append(v)
    out = ["<!DOCTYPE html><html><head><meta charset='utf-8'><title>Class report</title>",
           "<style>%s</style></head><body><h1>Class report</h1>" % STYLE,
           "<p>Isolation of student code: %s</p>" % html.escape(isolation or "not recorded")]
    out += _glance(verdicts, order, report_dir)
    out += similarity.html_section(similar)
    out += ["<h2>Verdicts</h2>",
            "<p><input id='filter' hidden placeholder='filter: student, milestone, or milestone:cause' size='50' "
            "oninput='filterRows(this.value)'></p>",
            "<table id='verdicts'><tr><th class='sort left'>student</th>%s<th class='sort'>total</th></tr>"
            % "".join("<th class='sort'>%s</th>" % html.escape(m.name) for m in milestones)]
    for student, graded in by_student.items():
        named = {v.milestone.name: v for v in graded}
        cells = "".join(_cell(named[m.name], "%s-%s" % (student, m.name)) if m.name in named else "<td></td>"
                        for m in milestones)
        total = sum(v.points for v in graded)
        groups = " ".join("%s:%s" % (v.milestone.name, v.cause_key) for v in graded if not v.passed)
        out.append('<tr data-groups="%s"><th class="left"><a href="#%s">%s</a></th>%s<td>%g / %g</td></tr>' % (
            html.escape(groups), html.escape(student), html.escape(student), cells, total,
            sum(v.milestone.points for v in graded)))
    out.append("</table>")
    for student, graded in by_student.items():
        out.append('<h2 id="%s">%s</h2>' % (html.escape(student), html.escape(student)))
        for v in graded:
            out.append('<h3 id="%s-%s" class="%s">%s: %s (%s) &mdash; %s, %.1f s</h3>' % (
                html.escape(student), html.escape(v.milestone.name), "pass" if v.passed else "fail",
                html.escape(v.milestone.name), html.escape(v.milestone.title), html.escape(v.milestone.text),
                "passed" if v.passed else "failed (%s)" % html.escape(v.cause_key), v.elapsed))
            if not v.passed or v.logs or v.notes:
                out.append("<pre>%s</pre>" % html.escape(v.output()))
            for png in v.canvases():
                rel = os.path.relpath(png, report_dir)
                out.append('<a href="%s"><img src="%s" alt="%s"></a>' % (html.escape(rel), html.escape(rel),
                                                                          html.escape(os.path.basename(png))))
    out.append(SCRIPT)
    out.append("</body></html>")
    return "\n".join(out)


def write(path: str, verdicts: Sequence[Verdict], order: Sequence[Milestone], isolation: str = "",
          similar: Sequence[similarity.Pair] = ()) -> None:
    with open(path, "w") as f:
        f.write(render(verdicts, order, os.path.dirname(os.path.abspath(path)), isolation, similar))
