#!/usr/bin/env bash
# A throw-away Debian 12 root for the fresh-machine check (tools/fresh_debian_check.sh): it
# prepares and releases the chroot.
#
#   bash tools/chroot_root.sh bootstrap DIR   # debootstrap --variant=minbase bookworm into DIR
#   bash tools/chroot_root.sh prepare DIR     # mounts, /etc/hosts, DNS, CA certificates, pip config
#   bash tools/chroot_root.sh release DIR     # unmount everything under DIR (safe to repeat)
#
# Needs root. The host's CA bundle and pip config go in so the chroot reaches the same package
# registries as the host. `release` reads /proc/mounts rather than remembering what `prepare`
# mounted, so a caller that was interrupted half-way can still release, and fails if anything is
# left mounted: the caller must not delete DIR then (it would reach into the host's /dev).
set -eo pipefail

usage() { echo "usage: $0 bootstrap|prepare|release DIR" >&2; exit 2; }
[ "$#" -eq 2 ] || usage
action="$1"
target="$(realpath -m "$2")"
[ "$(id -u)" -eq 0 ] || { echo "chroot_root: needs root (debootstrap, chroot, mount)" >&2; exit 2; }
[ "$target" != "/" ] || { echo "chroot_root: refusing DIR=/" >&2; exit 2; }

bootstrap() {
  command -v debootstrap >/dev/null || { apt-get update -qq && apt-get install -y -qq debootstrap >/dev/null; }
  local mirror
  mirror="$(sed -n 's/^URIs: *//p' /etc/apt/sources.list.d/debian.sources 2>/dev/null | head -n1)"
  debootstrap --variant=minbase bookworm "$target" "${mirror:-http://deb.debian.org/debian}"
}

prepare() {
  local fs
  for fs in proc sys dev dev/pts; do
    mkdir -p "$target/$fs"
    mountpoint -q "$target/$fs" || mount --bind "/$fs" "$target/$fs"
  done
  # A world-writable /dev/shm as on a real machine or in a container (the bind above does not
  # carry the host's /dev/shm mount): non-root users' POSIX semaphores and shared memory.
  mountpoint -q "$target/dev/shm" || mount -t tmpfs -o mode=1777,nosuid,nodev shm "$target/dev/shm"
  # As Debian's installer writes it: localhost, and this machine's name on 127.0.1.1 (the chroot
  # shares the host's name; tools such as roswtf resolve it).
  printf '127.0.0.1 localhost\n127.0.1.1 %s\n::1 localhost ip6-localhost ip6-loopback\n' "$(hostname)" \
    > "$target/etc/hosts"
  cp /etc/resolv.conf "$target/etc/resolv.conf" 2>/dev/null || true
  # The host's CA bundle both as the chroot's bundle now and as a local CA, so that installing
  # ca-certificates in the chroot (update-ca-certificates rewrites the bundle) keeps it.
  mkdir -p "$target/usr/local/share/ca-certificates/host" "$target/etc/ssl/certs"
  cp /etc/ssl/certs/ca-certificates.crt "$target/etc/ssl/certs/ca-certificates.crt"
  cp /etc/ssl/certs/ca-certificates.crt "$target/usr/local/share/ca-certificates/host/host-bundle.crt"
  if [ -f /etc/pip.conf ]; then cp /etc/pip.conf "$target/etc/pip.conf"; fi
}

mounts_under() {  # the mount points at or below $target, deepest first
  awk -v t="$target" '$2 == t || index($2, t "/") == 1 { print $2 }' /proc/mounts | sort -r
}

release() {
  local point
  for point in $(mounts_under); do umount -l "$point" 2>/dev/null || true; done
  if [ -n "$(mounts_under)" ]; then
    echo "chroot_root: still mounted under $target:" $(mounts_under) >&2
    exit 1
  fi
}

case "$action" in
  bootstrap) bootstrap ;;
  prepare) prepare ;;
  release) release ;;
  *) usage ;;
esac
