"""`python3 -m course_milestones.launch_dump PATH [name:=value ...]`: load a launch file with
roslaunch's own parser and print, as one JSON object on stdout, what the checks need of it.

Loading a student's launch file runs the student's code: `$(eval ...)` is Python, `<param
command="...">` a shell command, `textfile=`, `binfile=` and `<rosparam file=...>` read any file.
So it never happens in a check's process: course_milestones.launch_files runs this module in a
process of its own, through the students' sandbox, and reads its output as untrusted data.

The output, one line of JSON (FORMAT below), is either
  {"format": FORMAT, "params": {name: value}, "nodes": [{"package", "type", "name", "namespace",
   "args", "remap_args": [[from, to]], "env_args": [[name, value]]}]}
with exit code 0, or {"format": FORMAT, "error": "roslaunch's reason"} with exit code 2.
Parameter values are JSON's (roslaunch's XML-RPC values: numbers, strings, booleans, lists,
dicts); anything else (a binfile's bytes, a YAML date) is given as its repr.
"""
from __future__ import annotations

import json
import os
import sys
from typing import Dict, List, Optional, Sequence

FORMAT = "course_milestones.launch_dump/1"
MAX_DEPTH = 32                  # nesting kept in a parameter value; deeper is given as a repr
MAX_OUTPUT_BYTES = 1000 * 1000  # below the sandbox's 1 MB capture: a longer dump is an error instead


def plain(value: object, depth: int = 0) -> object:
    """`value` as JSON can carry it (see the module's docstring)."""
    if value is None or isinstance(value, (bool, int, float, str)):
        return value
    if depth < MAX_DEPTH and isinstance(value, (list, tuple)):
        return [plain(v, depth + 1) for v in value]
    if depth < MAX_DEPTH and isinstance(value, dict):
        return {str(k): plain(v, depth + 1) for k, v in value.items()}
    return repr(value)[:10000]


def describe(config) -> Dict[str, object]:
    """The parameters and nodes of a loaded roslaunch.config.ROSLaunchConfig."""
    params = {key: plain(p.value) for key, p in config.params.items()}
    nodes: List[Dict[str, object]] = []
    for node in config.nodes:
        nodes.append({"package": node.package, "type": node.type, "name": node.name,
                      "namespace": node.namespace, "args": node.args or "",
                      "remap_args": [[str(a), str(b)] for a, b in node.remap_args or []],
                      "env_args": [[str(a), str(b)] for a, b in node.env_args or []]})
    return {"format": FORMAT, "params": params, "nodes": nodes}


def main(argv: Optional[Sequence[str]] = None) -> int:
    """Load argv[1] (with roslaunch's `name:=value` args after it) and print the JSON."""
    argv = list(sys.argv if argv is None else argv)
    if len(argv) < 2:
        sys.stderr.write("usage: python3 -m course_milestones.launch_dump PATH [name:=value ...]\n")
        return 64
    # Only our JSON goes to stdout: whatever the file makes print (an $(eval) print(), roslaunch's
    # own messages) goes to stderr, so it cannot spoil the answer by accident.
    out = os.fdopen(os.dup(1), "w", encoding="utf-8")
    os.dup2(2, 1)
    sys.stdout = sys.stderr
    try:
        import roslaunch.config
        sys.argv = argv  # roslaunch reads the file's args (name:=value) from sys.argv
        answer = describe(roslaunch.config.load_config_default([argv[1]], None))
        code = 0
    except Exception as err:  # noqa: BLE001 - the student's $(eval) may raise anything: it is the answer
        answer = {"format": FORMAT, "error": ("%s" % err).strip() or type(err).__name__}
        code = 2
    text = json.dumps(answer, ensure_ascii=True)
    if len(text) > MAX_OUTPUT_BYTES:
        text = json.dumps({"format": FORMAT, "error": "its parameters and nodes take more than %d bytes"
                           % MAX_OUTPUT_BYTES})
        code = 2
    out.write(text + "\n")
    out.flush()
    return code


if __name__ == "__main__":
    sys.exit(main())
