"""setup/install.sh (make deps, make build) prints one line per set-up step with its time, apt's and
pip's output going to the log the line names; a failing step prints its log's last lines and exits
non-zero. Run on a copy of the script in a temporary checkout, apt-get, dpkg-query, sudo and useradd
replaced by stand-ins on PATH: nothing is installed, nothing is fetched."""
from __future__ import annotations

import hashlib
import os
import re
import shutil
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
APT_LINES = 100  # what the stand-in apt-get prints
STAND_INS = {
    "dpkg-query": "exit 1",  # nothing is installed
    "apt-get": 'for i in $(seq 1 %d); do echo "apt line $i"; done; [ "$1" = update ] || exit "${APT_EXIT:-0}"'
               % APT_LINES,
    "sudo": '[ "$1" = -v ] && exit 0; exec "$@"',
    "useradd": "exit 0",
}


def checkout(tmp_path: Path) -> Path:
    """A checkout holding setup/install.sh, one Debian package to install and a course venv up to date."""
    root = tmp_path / "course"
    (root / "setup").mkdir(parents=True)
    shutil.copy(ROOT / "setup" / "install.sh", root / "setup" / "install.sh")
    (root / "setup" / "apt-packages.txt").write_text("# one package\nros-core-dev\n")
    requirements = root / "requirements.txt"
    requirements.write_text("roslibpy==2.1.0\n")
    python = root / ".venv" / "bin" / "python3"
    python.parent.mkdir(parents=True)
    python.write_text("#!/bin/sh\nexit 0\n")
    python.chmod(0o755)
    (root / ".venv" / ".requirements.sha256").write_text(hashlib.sha256(requirements.read_bytes()).hexdigest() + "\n")
    shims = tmp_path / "bin"
    shims.mkdir()
    for name, body in STAND_INS.items():
        (shims / name).write_text("#!/bin/bash\n%s\n" % body)
        (shims / name).chmod(0o755)
    return root


def deps(root: Path, **env: str) -> subprocess.CompletedProcess:
    environ = dict(os.environ, PATH="%s:%s" % (root.parent / "bin", os.environ["PATH"]), COURSE_JUPYTER="0",
                   COURSE_HUB="0", **env)
    return subprocess.run(["bash", str(root / "setup" / "install.sh")], env=environ, stdin=subprocess.DEVNULL,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=60, check=False)


def test_each_step_is_one_line_with_its_time_and_its_log(tmp_path):
    root = checkout(tmp_path)
    done = deps(root)
    assert done.returncode == 0, done.stdout + done.stderr
    assert re.fullmatch(r"\[1/2\] Debian packages: 1 to install with apt(, the sandbox user coursesandbox)? "
                        r"\(log: logs/apt.log\) \.\.\. \d+ s\n"
                        r"\[2/2\] the course's PyPI packages in \.venv \.\.\. up to date\n", done.stdout), done.stdout
    assert done.stderr == ""
    log = (root / "logs" / "apt.log").read_text()
    assert "apt line 1\n" in log and "apt line %d\n" % APT_LINES in log  # apt-get update's and install's


def test_a_failing_step_prints_its_logs_tail_and_exits_non_zero(tmp_path):
    root = checkout(tmp_path)
    done = deps(root, APT_EXIT="100")
    assert done.returncode != 0
    assert re.fullmatch(r"\[1/2\] Debian packages: .* \(log: logs/apt.log\) \.\.\. FAILED after \d+ s \(exit 100\)\n",
                        done.stdout), done.stdout  # the steps after it do not run
    tail = [line for line in done.stderr.splitlines() if line.startswith("apt line")]
    assert tail == ["apt line %d" % i for i in range(APT_LINES - 29, APT_LINES + 1)]  # the last 30 lines
    assert "logs/apt.log" in done.stderr
