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


def test_make_tests_hub_venv_step_installs_the_hubs_venv_alone_then_is_up_to_date(tmp_path):
    """`install.sh --hub-venv` (make test): the hub's venv and course_hub in it, two steps, no apt, no
    podman, no npm; a second run finds both up to date."""
    root = checkout(tmp_path)
    (root / "requirements-hub.txt").write_text("jupyterhub==6.1.1\n")
    package = root / "src" / "course_hub"
    (package / "src" / "course_hub").mkdir(parents=True)
    (package / "pyproject.toml").write_text("[project]\nname = 'course_hub'\n")
    (package / "src" / "course_hub" / "__init__.py").write_text("")
    hub_python = root / ".venv-hub" / "bin" / "python3"  # the venv made already; pip a stand-in that succeeds
    hub_python.parent.mkdir(parents=True)
    hub_python.write_text("#!/bin/sh\nexit 0\n")
    hub_python.chmod(0o755)
    (tmp_path / "bin" / "apt-get").write_text("#!/bin/sh\necho apt-get ran >&2\nexit 1\n")
    for run, result in (("first", r"\d+ s"), ("second", "up to date")):
        done = subprocess.run(["bash", str(root / "setup" / "install.sh"), "--hub-venv"],
                              env=dict(os.environ, PATH="%s:%s" % (tmp_path / "bin", os.environ["PATH"])),
                              stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                              timeout=60, check=False)
        assert done.returncode == 0 and done.stderr == "", (run, done.stdout, done.stderr)
        lines = done.stdout.splitlines()
        assert len(lines) == 2 and all(line.startswith("[%d/2] " % n) for n, line in enumerate(lines, 1)), lines
        assert "JupyterHub" in lines[0] and "course_hub" in lines[1], lines
        assert all(re.search(result + "$", line) for line in lines), (run, lines)
