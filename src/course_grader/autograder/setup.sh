#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder image; the zip is unpacked
# in /autograder/source. It installs and builds the course workspace exactly as
# `make build` does (docs/setup.md: Debian/Ubuntu packages, the venv, catkin_make).
set -euo pipefail
source_dir="$(cd "$(dirname "$0")" && pwd)"
cd "$source_dir"
if ! command -v make >/dev/null; then
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends make ca-certificates python3 python3-venv
fi
[ -e catkin_ws/src ] || ln -s ../src catkin_ws/src
COURSE_JUPYTER=0 make build  # no student's workbench (JupyterLab) in a grading image
chmod +x "$source_dir/run_autograder"
