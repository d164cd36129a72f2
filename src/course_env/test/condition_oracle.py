"""catkin_pkg's evaluate_condition() verdicts, one JSON line in, one out: the oracle processes of
test_pyparsing_deferral's property test, one with course_env's usercustomize, one without.

    python3 condition_oracle.py hooked|upstream

First line out: {"pyparsing_loaded": whether catkin_pkg.package's import loaded pyparsing}.
Each line in: [condition or null, {name: value}]. Each line out: ["ok", result] or
["error", exception type, message].
"""
from __future__ import annotations

import json
import sys


def main() -> None:
    import catkin_pkg.package  # noqa: F401 - what every rospy process imports (through roslib)
    print(json.dumps({"pyparsing_loaded": "pyparsing" in sys.modules}), flush=True)
    from catkin_pkg.condition import evaluate_condition
    for line in sys.stdin:
        condition, context = json.loads(line)
        try:
            answer = ["ok", evaluate_condition(condition, context)]
        except Exception as error:  # noqa: BLE001 - the verdict is the exception's type and words
            answer = ["error", type(error).__name__, str(error)]
        print(json.dumps(answer), flush=True)


if __name__ == "__main__":
    main()
