"""Hunt flaky tests: the suite's JUnit XML from K runs, tallied per test.

A flake shows up as a test that fails in some runs and passes in others. To find its cause we
need, per test, how often it ran and failed and what it said the first time it failed; per run,
how long it took and whether pytest produced results at all. pytest's JUnit XML carries a
one-paragraph `message` attribute per failure (the assertion text, no traceback): its first
line is what the report shows, joined with the next one when it only introduces it
("rostest x failed:").
"""
from __future__ import annotations

import xml.etree.ElementTree as ET
from typing import Dict, Iterable, List, NamedTuple, Optional, Sequence, Tuple

PASSED, FAILED, SKIPPED = "passed", "failed", "skipped"
# A failure line longer than this is cut, so the report stays one line per test.
MESSAGE_CHARS = 160


class Outcome(NamedTuple):
    """One test in one run: `status` is PASSED, FAILED (a failure or an error) or SKIPPED."""
    test_id: str
    status: str
    message: str


class Run(NamedTuple):
    """One run of the suite: `outcomes` is None when pytest left no readable JUnit XML."""
    index: int
    seconds: float
    returncode: int
    outcomes: Optional[Tuple[Outcome, ...]]

    @property
    def failed(self) -> bool:
        return self.returncode != 0 or self.outcomes is None or any(o.status == FAILED for o in self.outcomes)


class Tally(NamedTuple):
    """One test over all runs: runs that ran it (skips excluded), its failures, the first failure."""
    runs: int
    failures: int
    skips: int
    first_failed_run: Optional[int]
    first_message: str


def first_line(message: str, limit: int = MESSAGE_CHARS) -> str:
    """The message's first non-empty line, with the next one when the first ends with ':'."""
    lines = [line.strip() for line in (message or "").splitlines() if line.strip()]
    if not lines:
        return ""
    line = lines[0]
    if line.endswith(":") and len(lines) > 1:
        line = "%s %s" % (line, lines[1])
    return line if len(line) <= limit else line[:limit - 3] + "..."


def _outcome(case: ET.Element) -> Outcome:
    classname, name = case.get("classname", ""), case.get("name", "?")
    test_id = "%s::%s" % (classname, name) if classname else name
    for tag in ("failure", "error"):
        found = case.find(tag)
        if found is not None:
            return Outcome(test_id, FAILED, first_line(found.get("message") or found.text or tag))
    if case.find("skipped") is not None:
        return Outcome(test_id, SKIPPED, "")
    return Outcome(test_id, PASSED, "")


def parse_outcomes(xml_text: str) -> Tuple[Outcome, ...]:
    """Each test of one pytest JUnit document once; a test listed twice (a failure, then an
    error in its teardown) counts as failed with its first message."""
    merged: Dict[str, Outcome] = {}
    for case in ET.fromstring(xml_text).iter("testcase"):
        outcome = _outcome(case)
        known = merged.get(outcome.test_id)
        if known is None or (known.status != FAILED and outcome.status == FAILED):
            merged[outcome.test_id] = outcome
    return tuple(merged.values())


def read_outcomes(path: str) -> Optional[Tuple[Outcome, ...]]:
    """The outcomes in a JUnit file, or None when it is missing or not XML."""
    try:
        with open(path, "rb") as f:
            return parse_outcomes(f.read().decode("utf-8", errors="replace"))
    except (OSError, ET.ParseError):
        return None


def tally(runs: Iterable[Run]) -> Dict[str, Tally]:
    """Per test id, its Tally over `runs` (in run order)."""
    result: Dict[str, Tally] = {}
    for run in runs:
        for outcome in run.outcomes or ():
            seen = result.get(outcome.test_id, Tally(0, 0, 0, None, ""))
            if outcome.status == SKIPPED:
                seen = seen._replace(skips=seen.skips + 1)
            elif outcome.status == FAILED:
                first = seen.first_failed_run is None
                seen = seen._replace(runs=seen.runs + 1, failures=seen.failures + 1,
                                     first_failed_run=run.index if first else seen.first_failed_run,
                                     first_message=outcome.message if first else seen.first_message)
            else:
                seen = seen._replace(runs=seen.runs + 1)
            result[outcome.test_id] = seen
    return result


def any_failure(runs: Sequence[Run]) -> bool:
    return any(run.failed for run in runs)


def run_line(run: Run, total: Optional[int] = None) -> str:
    """One line per run: counts, exit code, wall time."""
    label = "run %d%s" % (run.index, "/%d" % total if total else "")
    if run.outcomes is None:
        return "%s: no JUnit results (pytest exit code %d) in %.1f s" % (label, run.returncode, run.seconds)
    counts = {status: sum(o.status == status for o in run.outcomes) for status in (PASSED, FAILED, SKIPPED)}
    return "%s: %d passed, %d failed, %d skipped (exit code %d) in %.1f s" % (
        label, counts[PASSED], counts[FAILED], counts[SKIPPED], run.returncode, run.seconds)


def report(runs: Sequence[Run], show_all: bool = False) -> str:
    """The whole report: per run, per test that failed at least once (or every test), totals."""
    tallies = tally(runs)
    lines: List[str] = ["Runs:"] + ["  " + run_line(run) for run in runs]
    shown = sorted(((test_id, t) for test_id, t in tallies.items() if show_all or t.failures),
                   key=lambda item: (-item[1].failures, item[0]))
    flaky = [test_id for test_id, t in tallies.items() if 0 < t.failures < t.runs]
    lines.append("Tests that failed at least once:" if not show_all else "Tests:")
    if not shown:
        lines.append("  none")
    for test_id, t in shown:
        lines.append("  %d/%d failed%s  %s%s" % (
            t.failures, t.runs, ", %d skipped" % t.skips if t.skips else "", test_id,
            "\n      first in run %d: %s" % (t.first_failed_run, t.first_message) if t.failures else ""))
    total = sum(run.seconds for run in runs)
    no_results = sum(run.outcomes is None for run in runs)
    lines.append("Totals: %d runs, %d failed, in %.1f s (%.1f s per run); %d tests, %d failed at least once "
                 "(%d flaky: failed in some runs and passed in others)%s" % (
                     len(runs), sum(run.failed for run in runs), total, total / len(runs) if runs else 0.0,
                     len(tallies), sum(t.failures > 0 for t in tallies.values()), len(flaky),
                     "; %d runs left no results" % no_results if no_results else ""))
    return "\n".join(lines)
