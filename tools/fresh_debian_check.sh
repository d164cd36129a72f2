#!/usr/bin/env bash
# Does the README hold on a fresh Debian 12? Debootstrap a minbase bookworm into a temp dir,
# copy this checkout in (without build products), install what the README says a fresh
# Debian needs before `make`, then run the README's two commands inside a chroot:
# `make demo` and `make test`. Reports each step's result and time, then cleans up.
#
#   sudo bash tools/fresh_debian_check.sh [--keep] [--only-demo]
#
# Needs root and debootstrap (installed if missing). The chroot is made, prepared (mounts, hosts,
# the host's CA certificates and pip config) and released by tools/chroot_root.sh.
set -eo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
keep=0
only_demo=0
for arg in "$@"; do
  case "$arg" in
    --keep) keep=1 ;;
    --only-demo) only_demo=1 ;;
    *) echo "usage: $0 [--keep] [--only-demo]" >&2; exit 2 ;;
  esac
done
[ "$(id -u)" -eq 0 ] || { echo "fresh_debian_check: needs root (debootstrap, chroot, mount)" >&2; exit 2; }
chroot_root=(bash "$root/tools/chroot_root.sh")

work="$(mktemp -d /var/tmp/fresh-debian.XXXXXX)"
target="$work/root"
log="$work/log"
mkdir -p "$log"

cleanup() {
  if ! "${chroot_root[@]}" release "$target"; then echo "left in place (still mounted): $work"; return; fi
  if [ "$keep" -eq 1 ]; then echo "kept: $work"; else rm -rf --one-file-system "$work"; fi
}
trap cleanup EXIT

results=()
step() {  # step NAME COMMAND...: run, time, record PASS/FAIL, keep the log
  local name="$1"; shift
  local start=$SECONDS
  if "$@" >"$log/$name.log" 2>&1; then
    results+=("PASS $name ($((SECONDS-start)) s)")
    return 0
  fi
  results+=("FAIL $name ($((SECONDS-start)) s): $(tail -n 3 "$log/$name.log" | tr '\n' ' ')")
  return 1
}

in_chroot() {
  chroot "$target" /usr/bin/env -i HOME=/root TERM=dumb LANG=C.UTF-8 \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin bash -c "$1"
}

bootstrap() { "${chroot_root[@]}" bootstrap "$target"; }

prepare() {
  "${chroot_root[@]}" prepare "$target"
  # A fresh clone of the committed checkout, as CI and a student get it (.git included; no build,
  # devel or venv; uncommitted changes left out).
  git clone -q "$root" "$target/course"
  [ -d "$root/../shared" ] && cp -r "$root/../shared" "$target/shared"
  true
}

# What the README says a fresh Debian needs before `make` (keep the two in step).
readme_prereqs() { in_chroot "apt-get update && apt-get install -y --no-install-recommends make sudo ca-certificates"; }
demo() { in_chroot "cd /course && make demo"; }
suite() { in_chroot "cd /course && make test"; }

ok=0
step debootstrap bootstrap && step prepare prepare && step readme-prerequisites readme_prereqs \
  && step make-demo demo && { [ "$only_demo" -eq 1 ] || step make-test suite; } && ok=1

echo "fresh Debian 12 (minbase bookworm) check:"
printf '  %s\n' "${results[@]}"
for name in make-demo make-test; do
  [ -f "$log/$name.log" ] && { echo "--- $name (last lines) ---"; tail -n 5 "$log/$name.log"; }
done
[ "$ok" -eq 1 ]
