#!/usr/bin/env bash
# Set up the workspace, idempotently, one line per step with its time:
#   [1/5] Debian packages: 79 to install with apt (log: logs/apt.log) ... 143 s
# apt's, pip's, npm's and catkin_make's output goes to the log the line names; a step that fails
# prints the last lines of its log and the script exits non-zero. Steps with nothing to do say so.
#   bash setup/install.sh           make deps: the Debian ROS 1 packages that are missing (apt-get update
#                                   first, only then), the sandbox user, the repo-local venvs with the
#                                   pinned PyPI packages (only when their requirements changed)
#   bash setup/install.sh --build   make build: the same, then catkin_make in catkin_ws and, where the
#                                   reference solutions are, in their overlay solutions_ws
#   bash setup/install.sh --hub-venv  make test's addition: the hub's venv alone (.venv-hub: JupyterHub,
#                                   ltiauthenticator, course_hub), whose unit tests run the hub's own code;
#                                   no podman, no proxy (COURSE_HUB=1 adds those for make hub)
# COURSE_JUPYTER=0 leaves JupyterLab out; COURSE_HUB=1 adds the class's hub (make hub, docs/hub.md).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
logs="$root/logs"
TAIL_LINES=30  # of a failed step's log; a failed build prints more (its first error is further up)
build=0
hub_venv_only=0
case "${1:-}" in
  --build) build=1 ;;
  --hub-venv) hub_venv_only=1 ;;
  "") ;;
  *) echo "usage: $0 [--build | --hub-venv]" >&2; exit 2 ;;
esac
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
have_solutions=0
compgen -G "$root/courses/robotics_labs/solution/*/package.xml" >/dev/null && have_solutions=1

steps_total=2  # the Debian packages, the course's venv
[ "${COURSE_JUPYTER:-1}" = 0 ] || steps_total=$((steps_total + 1))
[ "${COURSE_HUB:-0}" != 1 ] || steps_total=$((steps_total + 4))
[ "$build" -eq 0 ] || steps_total=$((steps_total + 1 + have_solutions))
[ "$hub_venv_only" -eq 0 ] || steps_total=2
step_no=0

# step_line TITLE: "[i/n] TITLE ... ", the result to follow on the same line.
step_line() {
  step_no=$((step_no + 1))
  printf '[%*d/%d] %s ... ' "${#steps_total}" "$step_no" "$steps_total" "$1"
}

# step_done TITLE RESULT: a step that had nothing to do ("present", "up to date").
step_done() {
  step_line "$1"
  echo "$2"
}

# step TITLE LOG TAIL COMMAND...: COMMAND's output into LOG (named on the line, relative to the
# checkout), its time after it; when it fails, LOG's last TAIL lines and exit 1.
step() {
  local title="$1" log="$2" tail_lines="$3" start=$SECONDS code=0
  shift 3
  mkdir -p "$(dirname "$log")"
  step_line "$title (log: ${log#"$root"/})"
  "$@" >"$log" 2>&1 || code=$?
  if [ "$code" -eq 0 ]; then
    echo "$((SECONDS - start)) s"
    return 0
  fi
  echo "FAILED after $((SECONDS - start)) s (exit $code)"
  echo "--- the last $tail_lines lines of ${log#"$root"/} ---" >&2
  tail -n "$tail_lines" "$log" >&2
  echo "--- (the whole log: $log)" >&2
  exit 1
}

# The steps' commands. Each chains its commands with && (set -e does not reach into a function
# whose status `step` tests).
apt_install() {  # apt_install PACKAGE...: apt-get update, then install them
  $sudo apt-get update && $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "$@"
}
pip_install() {  # pip_install DIR REQUIREMENTS STAMP SHA [venv options]: DIR made from /usr/bin/python3 once
  # A line `# unwanted: PKG...` in REQUIREMENTS names what a requirement's extra pulls in and the
  # venv must not keep: removed after the install.
  local dir="$1" requirements="$2" stamp="$3" sha="$4" unwanted
  shift 4
  unwanted="$(sed -n 's/^# unwanted: *//p' "$requirements")"
  { [ -x "$dir/bin/python3" ] || /usr/bin/python3 -m venv "$@" "$dir"; } \
    && "$dir/bin/python3" -m pip install --disable-pip-version-check -r "$requirements" \
    && { [ -z "$unwanted" ] || "$dir/bin/python3" -m pip uninstall --disable-pip-version-check -y $unwanted; } \
    && echo "$sha" > "$stamp"
}
package_install() {  # package_install VENV PACKAGE STAMP SHA: the Python package in folder PACKAGE into VENV
  # built from a copy of its pyproject.toml and src/, so that the build leaves nothing in the checkout
  local copy
  copy="$(mktemp -d)" && cp -r "$2/pyproject.toml" "$2/src" "$copy/" \
    && "$1/bin/python3" -m pip install --disable-pip-version-check --no-deps --force-reinstall "$copy" \
    && rm -rf "$copy" && echo "$4" > "$3"
}
npm_install() {  # npm_install DIR PACKAGE_JSON: the pinned node packages into DIR
  mkdir -p "$1" && cp "$2" "$1/package.json" && (cd "$1" && npm install --no-audit --no-fund --loglevel=error)
}
catkin_make_in() {  # catkin_make_in WS [UNDERLAY]: catkin_make in WS, UNDERLAY's setup.bash sourced first
  # in a bash of its own: ROS's setup.bash is not written for set -u
  bash -c '{ [ -z "$2" ] || source "$2/devel/setup.bash"; } && cd "$1" \
    && catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=Release' catkin_make_in "$1" "${2:-}"
}

missing_debs() {  # missing_debs PACKAGE...: those not installed
  local pkg
  for pkg in "$@"; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || echo "$pkg"
  done
}

# venv_step WHAT DIR REQUIREMENTS LOG [venv options]: REQUIREMENTS installed into DIR again only
# when the file changed (its sha256 is kept in DIR).
venv_step() {
  local what="$1" dir="$2" requirements="$3" log="$4" want_sha
  shift 4
  want_sha="$(sha256sum "$requirements" | cut -d' ' -f1)"
  if [ -x "$dir/bin/python3" ] && [ "$(cat "$dir/.requirements.sha256" 2>/dev/null)" = "$want_sha" ]; then
    step_done "$what in ${dir#"$root"/}" "up to date"
  else
    step "$what into ${dir#"$root"/} with pip" "$log" "$TAIL_LINES" \
      pip_install "$dir" "$requirements" "$dir/.requirements.sha256" "$want_sha" "$@"
  fi
}

# hub_venv: the hub's venv (.venv-hub, requirements-hub.txt: JupyterHub, its spawner, authenticators
# and culler), then course_hub, the course's JupyterHub plug-ins and the hub's commands (course-hub,
# course-hub-passwords), a package of that venv (src/course_hub/pyproject.toml; its dependencies are
# the pins), installed again whenever its sources change. Two steps: make hub's (COURSE_HUB=1), and
# make test's alone (--hub-venv), where course_hub's unit tests run JupyterHub from it.
hub_venv() {
  local hub_sha
  venv_step "JupyterHub" "$root/.venv-hub" "$root/requirements-hub.txt" "$logs/pip-venv-hub.log"
  hub_sha="$(cd "$root/src/course_hub" && find pyproject.toml src -type f -name '*.py' -o -name pyproject.toml \
    | LC_ALL=C sort | xargs sha256sum | sha256sum | cut -d' ' -f1)"
  if [ "$(cat "$root/.venv-hub/.course_hub.sha256" 2>/dev/null)" = "$hub_sha" ]; then
    step_done "course_hub in .venv-hub" "up to date"
  else
    step "course_hub into .venv-hub with pip" "$logs/pip-course-hub.log" "$TAIL_LINES" \
      package_install "$root/.venv-hub" "$root/src/course_hub" "$root/.venv-hub/.course_hub.sha256" "$hub_sha"
  fi
}
if [ "$hub_venv_only" -eq 1 ]; then
  hub_venv
  exit 0
fi

# Debian's ROS packages, and the sandbox user (course_sandbox: graded student code runs as
# coursesandbox when the grader is root).
mapfile -t wanted < <(grep -v -e '^#' -e '^[[:space:]]*$' "$root/setup/apt-packages.txt")
mapfile -t missing < <(missing_debs "${wanted[@]}")
need_user=0
[ "$(id -u)" -ne 0 ] || getent passwd coursesandbox >/dev/null || need_user=1
system_setup() {
  { [ "${#missing[@]}" -eq 0 ] || apt_install "${missing[@]}"; } \
    && { [ "$need_user" -eq 0 ] || useradd --system --no-create-home --home-dir /nonexistent \
           --shell /usr/sbin/nologin coursesandbox; }
}
if [ "${#missing[@]}" -gt 0 ] || [ "$need_user" -eq 1 ]; then
  title="Debian packages: ${#missing[@]} to install with apt"
  [ "$need_user" -eq 0 ] || title="$title, the sandbox user coursesandbox"
  [ "${#missing[@]}" -eq 0 ] || [ -z "$sudo" ] || sudo -v  # the password asked here, not behind the line
  step "$title" "$logs/apt.log" "$TAIL_LINES" system_setup
else
  step_done "Debian packages" "present"
fi

# The course's venv: Debian's ROS packages (rospy, PyQt5) stay visible.
venv_step "the course's PyPI packages" "$root/.venv" "$root/requirements.txt" "$logs/pip-venv.log" \
  --system-site-packages

# The student's workbench (make jupyter): JupyterLab in a venv of its own, apart from the course's
# (its tornado, pyzmq, jinja2 ... are newer than Debian's, which the course's nodes use).
# COURSE_JUPYTER=0 leaves it out (the Gradescope autograder's image grades, nobody works in it).
if [ "${COURSE_JUPYTER:-1}" != 0 ]; then
  venv_step "JupyterLab" "$root/.venv-jupyter" "$root/requirements-jupyter.txt" \
    "$logs/pip-venv-jupyter.log"
fi

# The class's hub (make hub, docs/hub.md): podman and runc (the containers), node and npm (the proxy),
# JupyterHub, DockerSpawner and the idle culler in a venv of their own (.venv-hub), and npm's
# configurable-http-proxy in a local prefix (.hub/node, pinned in deploy/jupyterhub/package.json).
if [ "${COURSE_HUB:-0}" = 1 ]; then
  # netavark: the network stack the hub asks podman for (course_hub.runner); iptables: the hub's
  # API port closed to the network (course_hub.firewall); libnss-myhostname: the machine's own
  # programs resolve the hub's <user>.hub.localhost names to loopback, as browsers do; iproute2:
  # make hub-check's test host (ip netns) and its ss
  mapfile -t hub_missing < <(missing_debs podman runc netavark iptables libnss-myhostname iproute2)
  # npm: Debian's nodejs and npm, unless a node that brings its own npm (nodesource's) is there
  command -v npm >/dev/null || hub_missing+=(nodejs npm)
  if [ "${#hub_missing[@]}" -gt 0 ]; then
    [ -z "$sudo" ] || sudo -v
    step "the hub's Debian packages: ${hub_missing[*]} with apt" "$logs/hub-apt.log" "$TAIL_LINES" \
      apt_install "${hub_missing[@]}"
  else
    step_done "the hub's Debian packages" "present"
  fi
  # podman's --userns=auto (each student container in a user namespace of its own) takes its
  # ranges from the `containers` entries (course_hub.spawner's userns)
  for ids in /etc/subuid /etc/subgid; do
    grep -q '^containers:' "$ids" 2>/dev/null || echo "containers:1000000:1000000000" >> "$ids"
  done
  hub_venv
  node_dir="$root/.hub/node"
  if ! cmp -s "$root/deploy/jupyterhub/package.json" "$node_dir/package.json" \
     || [ ! -x "$node_dir/node_modules/.bin/configurable-http-proxy" ]; then
    step "configurable-http-proxy into .hub/node with npm" "$logs/npm-hub.log" "$TAIL_LINES" \
      npm_install "$node_dir" "$root/deploy/jupyterhub/package.json"
  else
    step_done "configurable-http-proxy in .hub/node" "up to date"
  fi
fi

# The build: the course (infrastructure only) in catkin_ws; the reference solutions (courses/robotics_labs/solution/,
# under the texts' package names) an overlay of their own, solutions_ws, chained on it. The student
# image has no course solution/ and so no overlay.
if [ "$build" -eq 1 ]; then
  step "catkin_make in catkin_ws, the course" "$root/catkin_ws/build.log" 60 catkin_make_in "$root/catkin_ws"
  if [ "$have_solutions" -eq 1 ]; then
    step "catkin_make in solutions_ws, the reference solutions" "$root/solutions_ws/build.log" 60 \
      catkin_make_in "$root/solutions_ws" "$root/catkin_ws"
  fi
fi
