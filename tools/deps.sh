#!/usr/bin/env bash
# Install what the workspace needs, idempotently: the Debian ROS 1 packages that
# are missing (apt-get update first, only when something is missing), then the
# repo-local venv with the pinned PyPI packages (only when requirements changed).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"

mapfile -t wanted < <(grep -v -e '^#' -e '^[[:space:]]*$' "$root/tools/apt-packages.txt")
missing=()
for pkg in "${wanted[@]}"; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done
if [ "${#missing[@]}" -gt 0 ]; then
  echo "deps: installing ${#missing[@]} Debian packages: ${missing[*]}"
  $sudo apt-get update
  $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
else
  echo "deps: Debian packages present"
fi

# course_sandbox: the unprivileged user that graded student code runs as when the grader is root.
if [ "$(id -u)" -eq 0 ] && ! getent passwd coursesandbox >/dev/null; then
  useradd --system --no-create-home --home-dir /nonexistent --shell /usr/sbin/nologin coursesandbox
  echo "deps: created the sandbox user coursesandbox"
fi

# venv DIR REQUIREMENTS WHAT [venv options]: DIR made from /usr/bin/python3 once, REQUIREMENTS
# installed into it again only when the file changed (its sha256 is kept in DIR).
venv() {
  local dir="$1" requirements="$2" what="$3"
  shift 3
  local stamp="$dir/.requirements.sha256" want_sha
  want_sha="$(sha256sum "$requirements" | cut -d' ' -f1)"
  if [ ! -x "$dir/bin/python3" ]; then
    /usr/bin/python3 -m venv "$@" "$dir"
  fi
  if [ "$(cat "$stamp" 2>/dev/null)" != "$want_sha" ]; then
    echo "deps: installing $what into $dir"
    "$dir/bin/python3" -m pip install --disable-pip-version-check -q -r "$requirements"
    echo "$want_sha" > "$stamp"
  else
    echo "deps: $what up to date in $dir"
  fi
}

# The course's venv: Debian's ROS packages (rospy, PyQt5) stay visible.
venv "$root/.venv" "$root/requirements.txt" "the PyPI packages" --system-site-packages

# The student's workbench (make jupyter): JupyterLab in a venv of its own, apart from the course's
# (its tornado, pyzmq, jinja2 ... are newer than Debian's, which the course's nodes use).
# COURSE_JUPYTER=0 leaves it out (the Gradescope autograder's image grades, nobody works in it).
if [ "${COURSE_JUPYTER:-1}" != 0 ]; then
  venv "$root/.venv-jupyter" "$root/requirements-jupyter.txt" "JupyterLab"
fi

# The class's hub (make hub, docs/hub.md): podman and runc (the containers), node and npm (the proxy),
# JupyterHub, DockerSpawner and the idle culler in a venv of their own (.venv-hub), and npm's
# configurable-http-proxy in a local prefix (.hub/node, pinned in deploy/jupyterhub/package.json).
if [ "${COURSE_HUB:-0}" = 1 ]; then
  hub_missing=()
  # netavark: the network stack the hub asks podman for (course_hub.runner); iptables: the hub's
  # API port closed to the network (course_hub.firewall); libnss-myhostname: the machine's own
  # programs resolve the hub's <user>.hub.localhost names to loopback, as browsers do; iproute2:
  # make hub-check's test host (ip netns) and its ss
  for pkg in podman runc netavark iptables libnss-myhostname iproute2; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || hub_missing+=("$pkg")
  done
  # npm: Debian's nodejs and npm, unless a node that brings its own npm (nodesource's) is there
  command -v npm >/dev/null || hub_missing+=(nodejs npm)
  if [ "${#hub_missing[@]}" -gt 0 ]; then
    echo "deps: installing the hub's Debian packages: ${hub_missing[*]}"
    $sudo apt-get update
    $sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${hub_missing[@]}"
  fi
  # podman's --userns=auto (each student container in a user namespace of its own) takes its
  # ranges from the `containers` entries (course_hub.hubconfig)
  for ids in /etc/subuid /etc/subgid; do
    grep -q '^containers:' "$ids" 2>/dev/null || { echo "containers:1000000:1000000000" >> "$ids"; echo "deps: $ids: containers:1000000:1000000000 (podman's user namespaces)"; }
  done
  venv "$root/.venv-hub" "$root/requirements-hub.txt" "JupyterHub"
  node_dir="$root/.hub/node"
  if ! cmp -s "$root/deploy/jupyterhub/package.json" "$node_dir/package.json" \
     || [ ! -x "$node_dir/node_modules/.bin/configurable-http-proxy" ]; then
    echo "deps: installing configurable-http-proxy into $node_dir"
    mkdir -p "$node_dir"
    cp "$root/deploy/jupyterhub/package.json" "$node_dir/package.json"
    (cd "$node_dir" && npm install --no-audit --no-fund --loglevel=error)
  else
    echo "deps: configurable-http-proxy up to date in $node_dir"
  fi
fi
