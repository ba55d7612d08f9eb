#!/usr/bin/env bash
# The README's commands on a fresh Debian 12 machine, as far as one machine can make one: a
# minimal Debian 12 root (debootstrap --variant=minbase) in a folder of its own, the project's
# committed HEAD cloned into it, and `deploy/maptr COMMAND` run inside it with chroot, so that
# every package the project needs is installed by deploy/maptr itself. Root only.
#
#   tools/fresh_root.sh [--keep] [--base DIR] [COMMAND]     COMMAND: test (default), run, build;
#   "test -R NAME" passes ctest's options
#
# The root gets its own /proc, /sys, /dev, a private /dev/shm and /tmp (tmpfs), and the host's
# resolv.conf for apt. A chroot shares the host's network namespace and cannot make network
# namespaces as a plain machine does: the host tests skip there, with their reason. --base DIR
# starts from a copy of a root made before (debootstrap's download is the slow part); the
# folder is removed at the end, mounts first, unless --keep. Exit: the command's.
set -euo pipefail
[ "$(id -u)" -eq 0 ] || { echo "fresh_root: run as root (debootstrap and chroot need it)" >&2; exit 2; }
command -v debootstrap >/dev/null || { echo "fresh_root: needs debootstrap (apt-get install debootstrap)" >&2; exit 2; }
keep=0
base=""
while [ $# -gt 0 ]; do
  case "$1" in
    --keep) keep=1; shift ;;
    --base) base="$2"; shift 2 ;;
    *) break ;;
  esac
done
cmd="${1:-test}"
src="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
root="$(mktemp -d "${TMPDIR:-/var/tmp}/maptr-fresh-root-XXXXXX")"
mounts=()
cleanup() {
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do umount -l "${mounts[$i]}" 2>/dev/null || true; done
  # Mounts made inside the root (`ip netns` binds /run/netns onto itself), deepest first.
  awk -v r="$root/" 'index($2, r) == 1 {print $2}' /proc/mounts | sort -r | while read -r m; do
    umount -l "$m" 2>/dev/null || true
  done
  if [ "$keep" -eq 0 ]; then rm -rf --one-file-system "$root"; else echo "fresh_root: kept $root" >&2; fi
}
trap cleanup EXIT
if [ -n "$base" ]; then
  cp -a "$base/." "$root/"
else
  debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian >&2
fi
cp /etc/resolv.conf "$root/etc/resolv.conf"
mount_in() {  # mount_in TYPE SOURCE TARGET [OPTIONS]
  mkdir -p "$root$3"
  mount -t "$1" ${4:+-o "$4"} "$2" "$root$3"
  mounts+=("$root$3")
}
mount_in proc proc /proc
mount_in sysfs sys /sys
mount --rbind /dev "$root/dev" && mount --make-rslave "$root/dev" && mounts+=("$root/dev")
mount_in tmpfs tmpfs /dev/shm mode=1777
mount_in tmpfs tmpfs /tmp mode=1777
# The committed HEAD, as CI clones it (no build folder, nothing uncommitted).
git clone -q "$src" "$root/maptr"
echo "fresh_root: $(git -C "$root/maptr" log -1 --format='%h %s' | cut -c1-80) in $root" >&2
# A host behind a TLS-intercepting proxy trusts the proxy's CA through NODE_EXTRA_CA_CERTS; the
# root gets that one file (npm's registry is reached through the same proxy), nothing else.
node_ca=()
if [ -n "${NODE_EXTRA_CA_CERTS:-}" ] && [ -f "$NODE_EXTRA_CA_CERTS" ]; then
  cp "$NODE_EXTRA_CA_CERTS" "$root/etc/extra-ca.crt"
  node_ca=(NODE_EXTRA_CA_CERTS=/etc/extra-ca.crt)
fi
# No git, no Node.js, nothing of the project's packages: deploy/maptr installs them.
chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root LANG=C.UTF-8 "${node_ca[@]}" \
  bash -c "cd /maptr && deploy/maptr $cmd"
