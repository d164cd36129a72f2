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

venv="$root/.venv"
stamp="$venv/.requirements.sha256"
want_sha="$(sha256sum "$root/requirements.txt" | cut -d' ' -f1)"
if [ ! -x "$venv/bin/python3" ]; then
  /usr/bin/python3 -m venv --system-site-packages "$venv"
fi
if [ "$(cat "$stamp" 2>/dev/null)" != "$want_sha" ]; then
  echo "deps: installing PyPI packages into $venv"
  "$venv/bin/python3" -m pip install --disable-pip-version-check -q -r "$root/requirements.txt"
  echo "$want_sha" > "$stamp"
else
  echo "deps: venv up to date"
fi
